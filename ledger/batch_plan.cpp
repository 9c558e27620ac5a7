#include "ledger/batch_plan.h"

#include <cassert>
#include <map>
#include <utility>

namespace zonesim::ledger {
namespace {

// The fields that differ, for a conflict's reason ("amount 5 stored, 7 sent").
std::string differences(const Transaction& sent, const Transaction& stored) {
  std::string out;
  auto field = [&](const char* name, auto a, auto b) {
    if (a == b) return;
    if (!out.empty()) out += ", ";
    out += std::string(name) + " " + std::to_string(b) + " stored, " + std::to_string(a) + " sent";
  };
  field("kind", int(sent.kind), int(stored.kind));
  field("item", sent.item, stored.item);
  field("amount", sent.amount, stored.amount);
  field("counterparty", sent.counterparty, stored.counterparty);
  field("price", sent.price, stored.price);
  field("score", sent.score, stored.score);
  return out;
}

}  // namespace

BatchPlan planBatch(std::span<const Transaction> batch) {
  BatchPlan plan;
  plan.slot.assign(batch.size(), BatchPlan::kInvalid);
  plan.invalid.resize(batch.size());
  // Ordered map: batches are small and this runs off the tick thread.
  std::map<std::pair<std::uint64_t, std::uint64_t>, std::size_t> slot_of_key;
  for (std::size_t i = 0; i < batch.size(); ++i) {
    if (auto reason = invalidReason(batch[i])) {
      plan.invalid[i] = "invalid transaction: " + *reason;
      continue;
    }
    auto [it, fresh] =
        slot_of_key.try_emplace({batch[i].player, batch[i].seq}, plan.to_store.size());
    if (fresh) plan.to_store.push_back(i);
    plan.slot[i] = it->second;
  }
  return plan;
}

std::vector<TxResult> batchResults(std::span<const Transaction> batch, const BatchPlan& plan,
                                   std::span<const KeyWrite> writes) {
  assert(writes.size() == plan.to_store.size());
  std::vector<TxResult> results(batch.size());
  for (std::size_t i = 0; i < batch.size(); ++i) {
    if (plan.slot[i] == BatchPlan::kInvalid) {
      results[i] = {TxStatus::Failed, plan.invalid[i]};
      continue;
    }
    const KeyWrite& write = writes[plan.slot[i]];
    if (write.inserted && plan.to_store[plan.slot[i]] == i) {
      results[i] = {TxStatus::Committed, {}};
    } else if (sameRequest(batch[i], write.stored)) {
      results[i] = {TxStatus::AlreadyCommitted, {}};
    } else {
      results[i] = {TxStatus::Conflict, describe(batch[i]) + " is stored with other content: " +
                                            differences(batch[i], write.stored)};
    }
  }
  return results;
}

}  // namespace zonesim::ledger
