#include "gateway/load_report.h"

#include <stdexcept>

#include "zonesim.h"

namespace zonesim::gateway {

LoadReport::LoadReport(dds_entity_t participant, dds_entity_t topic, const LoadIdentity& identity)
    : identity_(identity), qos_(dds::gatewayLoadQos()) {
  writer_ = dds::makePartitionWriter(participant, topic, "", qos_.get());
}

bool LoadReport::publish(std::size_t sessions, std::uint64_t logins) {
  zonesim_dds_GatewayLoad r{};
  r.gateway_id = identity_.gateway_id;
  r.incarnation = identity_.incarnation;
  r.address = identity_.public_address.address;
  r.port = identity_.public_address.port;
  r.sessions = std::uint32_t(sessions);
  r.max_sessions = identity_.max_sessions;
  r.logins = logins;
  return dds_write(writer_.writer.get(), &r) >= 0;
}

Endpoint publicAddress(const Endpoint& configured, const Endpoint& bound) {
  Endpoint e{configured.address != 0 ? configured.address : bound.address,
             configured.port != 0 ? configured.port : bound.port};
  if (e.address == 0)
    throw std::invalid_argument(
        "bound to every interface (0.0.0.0): give --public-address, the address players reach "
        "this gateway at, so the lobby can send them here");
  return e;
}

}  // namespace zonesim::gateway
