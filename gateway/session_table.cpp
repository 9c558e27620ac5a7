#include "gateway/session_table.h"

namespace zonesim::gateway {

namespace {
std::mt19937_64 seededFromOs() {
  std::random_device rd;
  std::seed_seq seq{rd(), rd(), rd(), rd(), rd(), rd(), rd(), rd()};
  return std::mt19937_64(seq);
}

template <typename Map, typename Key>
std::optional<SlotHandle> lookup(const Map& m, const Key& k) {
  auto it = m.find(k);
  if (it == m.end()) return std::nullopt;
  return it->second;
}
}  // namespace

SessionTable::SessionTable(std::uint32_t gateway_id, std::size_t max_sessions,
                           std::uint16_t incarnation)
    : gateway_id_(gateway_id & 0xFFFF),
      incarnation_(incarnation),
      max_sessions_(max_sessions),
      token_rng_(seededFromOs()) {}

std::uint64_t SessionTable::freshToken() {
  for (;;) {
    std::uint64_t t = token_rng_();
    // 0 means "no session" on the wire; a collision with a live token is astronomically rare.
    if (t != 0 && !by_token_.contains(t)) return t;
  }
}

std::uint64_t SessionTable::issuedId(std::uint32_t serial) const {
  return (std::uint64_t{incarnation_} << 48) | (std::uint64_t{gateway_id_} << 32) | serial;
}

std::optional<SlotHandle> SessionTable::create(const Endpoint& address, std::uint64_t client_nonce,
                                               std::int64_t now_ns,
                                               std::optional<std::uint64_t> player_id) {
  if (pool_.size() >= max_sessions_) return std::nullopt;
  Session s;
  s.token = freshToken();
  s.player_id = player_id ? *player_id : issuedId(++player_counter_);
  s.session_id = issuedId(++session_counter_);
  s.client_nonce = client_nonce;
  s.address = address;
  s.created_ns = s.last_heard_ns = now_ns;
  std::uint64_t token = s.token, player = s.player_id;
  SlotHandle h = pool_.insert(std::move(s));
  by_token_[token] = h;
  by_player_[player] = h;
  by_hello_[HelloKey{address, client_nonce}] = h;
  return h;
}

std::optional<SlotHandle> SessionTable::findByHello(const Endpoint& address,
                                                    std::uint64_t client_nonce) const {
  return lookup(by_hello_, HelloKey{address, client_nonce});
}

std::optional<SlotHandle> SessionTable::findByToken(std::uint64_t token) const {
  return lookup(by_token_, token);
}

std::optional<SlotHandle> SessionTable::findByPlayer(std::uint64_t player_id) const {
  return lookup(by_player_, player_id);
}

bool SessionTable::erase(SlotHandle h) {
  const Session* s = pool_.get(h);
  if (s == nullptr) return false;
  by_token_.erase(s->token);
  by_player_.erase(s->player_id);
  by_hello_.erase(HelloKey{s->address, s->client_nonce});
  return pool_.erase(h);
}

}  // namespace zonesim::gateway
