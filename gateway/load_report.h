#pragma once
// A gateway's load report to the lobby (topic zs_gateway_load): where players reach it and how
// many sessions it holds, written once a second by a gateway that takes connect tokens.

#include <cstdint>

#include "idl/dds_entity.h"
#include "idl/dds_qos.h"
#include "wire/udp_socket.h"

namespace zonesim::gateway {

/// What does not change between reports.
struct LoadIdentity {
  std::uint16_t gateway_id = 0;
  std::uint16_t incarnation = 0;
  Endpoint public_address;  ///< where players reach the gateway
  std::uint32_t max_sessions = 0;
};

/// Writes GatewayLoad samples on a participant's zs_gateway_load topic.
class LoadReport {
 public:
  /// Creates the writer; throws dds::DdsError on failure.
  LoadReport(dds_entity_t participant, dds_entity_t topic, const LoadIdentity& identity);

  /// Writes one report; false if the write failed (a lobby not keeping up: the next one will do).
  bool publish(std::size_t sessions, std::uint64_t logins);

 private:
  LoadIdentity identity_;
  dds::Qos qos_;
  dds::PartitionWriter writer_;
};

/// The address to publish: `configured` where given (its port 0: the bound one), else the bound
/// address. Throws std::invalid_argument if that leaves 0.0.0.0, which no player can reach.
Endpoint publicAddress(const Endpoint& configured, const Endpoint& bound);

}  // namespace zonesim::gateway
