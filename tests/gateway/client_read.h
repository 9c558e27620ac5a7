#pragma once
// What a test client reads from the gateway, checked as client_stub checks it: FlatBuffers
// datagrams (Welcome, Pong, Handoff) by the Verifier, lean frames (Spawn, StateBatch, Despawn)
// with the session's token.

#include <gtest/gtest.h>

#include <optional>
#include <span>
#include <utility>

#include "wire/downlink_frame.h"
#include "wire/wire_verify.h"

namespace zonesim::testing {

/// One datagram as read: one of the two is set if it passed.
struct ClientRead {
  const proto::Datagram* datagram = nullptr;    ///< aliases the bytes
  std::optional<gateway::DownlinkFrame> frame;  ///< its payload aliases the bytes
};

/// Checks bytes for the session with this token (0 before the Welcome); a drop fails the test.
inline ClientRead readAsClient(std::span<const std::uint8_t> bytes, std::uint64_t token) {
  ClientRead r;
  if (gateway::isDownlinkFrame(bytes)) {
    gateway::ParsedFrame p = gateway::parseFrame(bytes, token);
    EXPECT_TRUE(p.ok()) << gateway::dropReasonName(*p.drop);
    if (p.ok()) r.frame = std::move(p.frame);
    return r;
  }
  gateway::Verified v = gateway::verifyDatagram(bytes, gateway::Direction::ToClient);
  EXPECT_TRUE(v.ok()) << gateway::dropReasonName(v.reason);
  r.datagram = v.datagram;
  return r;
}

}  // namespace zonesim::testing
