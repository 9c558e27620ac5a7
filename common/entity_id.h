#pragma once
// 64-bit entity ids, globally unique without coordination: the creating rank in the top 16
// bits, a per-rank counter in the low 48. Ids never change when an entity migrates.

#include <cstdint>
#include <string>

#include "common/splitmix.h"

namespace zonesim {

/// A globally unique entity id; 0 is never issued and means "none".
struct EntityId {
  std::uint64_t value = 0;

  static constexpr int kCounterBits = 48;
  static constexpr std::uint64_t kCounterMask = (std::uint64_t{1} << kCounterBits) - 1;

  static constexpr EntityId make(std::uint32_t rank, std::uint64_t counter) {
    return EntityId{(std::uint64_t{rank} << kCounterBits) | (counter & kCounterMask)};
  }
  constexpr std::uint32_t creatorRank() const { return std::uint32_t(value >> kCounterBits); }
  constexpr std::uint64_t counter() const { return value & kCounterMask; }
  constexpr explicit operator bool() const { return value != 0; }
  friend constexpr auto operator<=>(EntityId, EntityId) = default;
};

/// Hands out ids for one creating rank (or gateway) counting from 1.
class EntityIdAllocator {
 public:
  explicit EntityIdAllocator(std::uint32_t rank) : rank_(rank) {}
  /// Resumes after `issued` ids (restart from a checkpoint).
  EntityIdAllocator(std::uint32_t rank, std::uint64_t issued) : rank_(rank), counter_(issued) {}
  EntityId next() { return EntityId::make(rank_, ++counter_); }
  std::uint64_t issued() const { return counter_; }

 private:
  std::uint32_t rank_;
  std::uint64_t counter_ = 0;
};

/// Order-independent digest of a set of ids: sums of mixed ids wrap mod 2^64, so any
/// partition of the set over ranks sums to the same value (checked with one allreduce).
struct IdSetDigest {
  std::uint64_t count = 0;
  std::uint64_t hash = 0;
  void add(EntityId id) {
    ++count;
    hash += splitmix64(id.value);
  }
  void remove(EntityId id) {
    --count;
    hash -= splitmix64(id.value);
  }
  void merge(const IdSetDigest& o) {
    count += o.count;
    hash += o.hash;
  }
  friend bool operator==(const IdSetDigest&, const IdSetDigest&) = default;
};

std::string toString(EntityId id);

}  // namespace zonesim
