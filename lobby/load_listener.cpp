#include "lobby/load_listener.h"

#include "idl/dds_take.h"
#include "zonesim.h"

namespace zonesim::lobby {

LoadListener::LoadListener(dds_domainid_t domain)
    : participant_(dds::makeParticipant(domain)),
      topics_(dds::makeTopics(participant_.get())),
      qos_(dds::gatewayLoadQos()) {
  reader_ =
      dds::makePartitionReader(participant_.get(), topics_.gateway_load.get(), "", qos_.get());
}

std::size_t LoadListener::take(GatewayDirectory& directory, std::int64_t now_ns) {
  return dds::takeAll<zonesim_dds_GatewayLoad>(
      reader_.reader.get(), [&](const zonesim_dds_GatewayLoad& s) {
        GatewayReport r;
        r.gateway_id = s.gateway_id;
        r.incarnation = s.incarnation;
        r.address = {s.address, s.port};
        r.sessions = s.sessions;
        r.max_sessions = s.max_sessions;
        r.logins = s.logins;
        // A report no player could use says nothing about where to send them.
        if (r.gateway_id != 0 && r.address.address != 0 && r.address.port != 0)
          directory.report(r, now_ns);
      });
}

}  // namespace zonesim::lobby
