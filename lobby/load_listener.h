#pragma once
// The lobby's DDS side: a reader of the gateways' load reports (zs_gateway_load), drained into
// the directory each time the lobby wakes.

#include <cstdint>

#include "idl/dds_entity.h"
#include "idl/dds_qos.h"
#include "idl/topics.h"
#include "lobby/gateway_directory.h"

namespace zonesim::lobby {

/// Reads zs_gateway_load on its own participant.
class LoadListener {
 public:
  /// Joins the domain; throws dds::DdsError on failure.
  explicit LoadListener(dds_domainid_t domain);

  /// Takes every pending report into the directory; returns how many.
  std::size_t take(GatewayDirectory& directory, std::int64_t now_ns);

 private:
  // Declared first so it is deleted last.
  dds::Entity participant_;
  dds::Topics topics_;
  dds::Qos qos_;
  dds::PartitionReader reader_;
};

}  // namespace zonesim::lobby
