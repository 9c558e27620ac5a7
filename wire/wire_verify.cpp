#include "wire/wire_verify.h"

#include <cmath>

#include "wire/datagram_checksum.h"
#include "wire/downlink_frame.h"

namespace zonesim::gateway {

namespace {

// Datagram -> message table -> vector: anything deeper or with more tables is not ours.
constexpr flatbuffers::uoffset_t kMaxDepth = 4;
constexpr flatbuffers::uoffset_t kMaxTables = 8;

bool finite(float v) {
  return std::isfinite(v);
}
bool coordinate(float v) {
  return finite(v) && std::fabs(v) <= kMaxCoordinate;
}
bool position(const proto::Vec3f& p) {
  return coordinate(p.x()) && coordinate(p.y()) && coordinate(p.z());
}

// A desired planar motion: |move| <= 1 (with slack for the client's rounding).
bool move(float x, float z) {
  return finite(x) && finite(z) && std::sqrt(double(x) * x + double(z) * z) <= 1.0 + kMoveEpsilon;
}

bool step(float v, float lo, float hi) {
  return finite(v) && v >= lo && v <= hi;
}

bool checkToGateway(const proto::Datagram& d) {
  switch (d.msg_type()) {
    case proto::Message::Hello: {
      const proto::Hello* h = d.msg_as_Hello();
      return h->client_nonce() != 0 &&
             (h->name() == nullptr || h->name()->size() <= kMaxNameBytes) &&
             (h->connect_token() == nullptr || h->connect_token()->size() <= kMaxConnectTokenBytes) &&
             (h->resume_token() == nullptr || h->resume_token()->size() <= kMaxConnectTokenBytes);
    }
    case proto::Message::Input: {
      const proto::Input* in = d.msg_as_Input();
      if (in->seq() == 0 || !move(in->move_x(), in->move_z())) return false;
      // Earlier ones: before this one, oldest first, each a valid move.
      if (const auto* earlier = in->earlier()) {
        if (earlier->size() > kMaxEarlierInputs) return false;
        std::uint32_t before = 0;
        for (const proto::InputMove* e : *earlier) {
          if (e->seq() <= before || e->seq() >= in->seq() || !move(e->move_x(), e->move_z()))
            return false;
          before = e->seq();
        }
      }
      return true;
    }
    case proto::Message::LeaderboardQuery: {
      auto n = d.msg_as_LeaderboardQuery()->count();
      return n >= 1 && n <= kMaxLeaderboardRows;
    }
    case proto::Message::Transaction: {
      const proto::Transaction* t = d.msg_as_Transaction();
      return t->seq() != 0 && t->decided() < t->seq() && t->kind() >= 1 &&
             t->kind() <= kMaxTransactionKind;
    }
    default:  // Ping and Bye carry nothing to range-check beyond the token
      return true;
  }
}

bool checkWelcome(const proto::Welcome& w) {
  const proto::Vec3f *lo = w.world_min(), *hi = w.world_max();
  if (lo == nullptr || hi == nullptr || !position(*lo) || !position(*hi)) return false;
  if (w.codec() == nullptr || !validCodec(*w.codec())) return false;
  if (!step(w.sim_dt(), 1e-4f, 1.0f)) return false;
  return w.token() != 0 && w.zone() >= 0 && finite(w.tick_rate()) && w.tick_rate() > 0 &&
         w.tick_rate() <= 1000 && lo->x() <= hi->x() && lo->y() <= hi->y() && lo->z() <= hi->z();
}

bool checkToClient(const proto::Datagram& d) {
  switch (d.msg_type()) {
    case proto::Message::Welcome:
      return checkWelcome(*d.msg_as_Welcome());
    case proto::Message::Handoff: {
      const proto::Handoff* h = d.msg_as_Handoff();
      return h->from_zone() >= -1 && h->to_zone() >= 0 && h->avatar_id() != 0;
    }
    case proto::Message::Leaderboard: {
      const proto::Leaderboard* l = d.msg_as_Leaderboard();
      return (l->rows() == nullptr || l->rows()->size() <= kMaxLeaderboardRows) &&
             (l->reason() == nullptr || l->reason()->size() <= kMaxReasonBytes);
    }
    case proto::Message::TransactionOutcome: {
      const proto::TransactionOutcome* o = d.msg_as_TransactionOutcome();
      return o->seq() != 0 && o->status() <= kMaxTransactionStatus &&
             (o->reason() == nullptr || o->reason()->size() <= kMaxReasonBytes);
    }
    default:  // Pong: timestamps are opaque to the check
      return true;
  }
}

bool allowed(proto::Message type, Direction direction) {
  switch (type) {
    case proto::Message::Hello:
    case proto::Message::Input:
    case proto::Message::Ping:
    case proto::Message::Bye:
    case proto::Message::Transaction:
    case proto::Message::LeaderboardQuery:
      return direction == Direction::ToGateway;
    case proto::Message::Welcome:
    case proto::Message::Pong:
    case proto::Message::Handoff:
    case proto::Message::TransactionOutcome:
    case proto::Message::Leaderboard:
      return direction == Direction::ToClient;
    default:  // StateBatch, Spawn and Despawn travel as lean frames (wire/downlink_frame.h)
      return false;
  }
}

}  // namespace

bool validCodec(const proto::CodecParams& c) {
  const proto::Vec3f &lo = c.world_min(), &hi = c.world_max();
  if (!position(lo) || !position(hi) || !(lo.x() < hi.x() && lo.y() < hi.y() && lo.z() < hi.z()))
    return false;
  // The same limits as the scene keys, so every field stays well under 32 bits; at most 2^20
  // interest cells.
  if (!step(c.cell_size(), 1e-3f, kMaxCoordinate)) return false;
  double columns = std::ceil((double(hi.x()) - lo.x()) / c.cell_size());
  double rows = std::ceil((double(hi.z()) - lo.z()) / c.cell_size());
  return columns * rows <= double(1 << 20) && step(c.position_resolution(), 1e-4f, 1) &&
         step(c.max_speed(), 1, 1e4f) && step(c.velocity_resolution(), 1e-4f, 1) &&
         step(c.max_acceleration(), 1, 1e4f) && step(c.acceleration_resolution(), 1e-4f, 1) &&
         step(c.max_angular_velocity(), 1, 1e3f) &&
         step(c.angular_velocity_resolution(), 1e-4f, 1) && c.rotation_bits() >= 4 &&
         c.rotation_bits() <= 16 &&
         (double(hi.y()) - lo.y()) / c.position_resolution() < double(1u << 30) &&
         c.cell_size() / c.position_resolution() < float(1u << 30);
}

std::optional<DropReason> checkFraming(std::span<const std::uint8_t>& bytes,
                                       bool (*has_identifier)(const void*),
                                       bool (*verify)(flatbuffers::Verifier&),
                                       VerifierLimits limits) {
  if (bytes.size() > kMaxDatagramBytes) return DropReason::TooLarge;
  if (bytes.size() < kMinDatagramBytes + kChecksumBytes) return DropReason::Truncated;
  if (!checksumMatches(bytes)) return DropReason::BadChecksum;
  bytes = bytes.first(bytes.size() - kChecksumBytes);
  if (!has_identifier(bytes.data())) return DropReason::BadIdentifier;
  flatbuffers::Verifier::Options opts;
  opts.max_depth = limits.max_depth;
  opts.max_tables = limits.max_tables;
  opts.check_alignment = true;
  flatbuffers::Verifier verifier(bytes.data(), bytes.size(), opts);
  if (!verify(verifier)) return DropReason::Malformed;
  return std::nullopt;
}

Verified verifyDatagram(std::span<const std::uint8_t> bytes, Direction direction) {
  if (auto drop = checkFraming(bytes, &proto::DatagramBufferHasIdentifier,
                               &proto::VerifyDatagramBuffer, {kMaxDepth, kMaxTables}))
    return {nullptr, *drop};
  // Ours start with a small root offset (wire_encode.cpp): this one would pass for a lean frame.
  if (isDownlinkFrame(bytes)) return {nullptr, DropReason::BadIdentifier};
  const proto::Datagram* d = proto::GetDatagram(bytes.data());
  proto::Message type = d->msg_type();
  // The Verifier accepts union types it does not know (forward compatibility): we do not.
  if (type == proto::Message::NONE || type > proto::Message::MAX || d->msg() == nullptr)
    return {nullptr, DropReason::NoMessage};
  if (!allowed(type, direction)) return {nullptr, DropReason::UnexpectedType};
  bool in_range = direction == Direction::ToGateway ? checkToGateway(*d) : checkToClient(*d);
  if (!in_range) return {nullptr, DropReason::OutOfRange};
  return {d, DropReason::Count};
}

}  // namespace zonesim::gateway
