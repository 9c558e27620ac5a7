// discovery: the service through which topology_node hosts and peers find each other
// (docs/networking.md, "Topologies").
#include <cstdio>
#include <optional>

#include "common/cli.h"
#include "common/stop_signal.h"
#include "common/text_file.h"
#include "topologies/discovery_service.h"

int main(int argc, char** argv) {
  CLI::App app{"zonesim discovery: hosts and peers register, clients and peers list them"};
  zonesim::CommonOptions common;
  zonesim::addCommonOptions(app, common);
  zonesim::ListenOptions listen_opts;
  zonesim::addListenOptions(app, listen_opts, "registrations and lists");
  double duration = 0;
  app.add_option("--duration", duration, "exit after this many seconds (0 = until signalled)")
      ->check(CLI::NonNegativeNumber);
  CLI11_PARSE(app, argc, argv);
  zonesim::installStopSignals();
  try {
    zonesim::applyCommonOptions(common, "discovery");
    std::string bind_option = zonesim::gateway::bindOptionText(listen_opts.bind, listen_opts.port);
    std::optional<zonesim::topo::DiscoveryService> service;
    try {
      service.emplace(zonesim::gateway::bindFromOptions(listen_opts.bind, listen_opts.port));
    } catch (const std::exception& e) {
      throw std::runtime_error(bind_option + ": " + e.what());
    }
    if (!listen_opts.port_file.empty())
      zonesim::writeTextFileAtomically(listen_opts.port_file,
                                       std::to_string(service->local().port));
    std::printf("discovery listening on %s\n", service->local().str().c_str());
    std::fflush(stdout);
    service->run(zonesim::stopRequested(), duration);
    const auto& c = service->counters();
    std::printf("discovery summary {\"registers\":%llu,\"lists\":%llu,\"errors\":%llu}\n",
                (unsigned long long)c.registers, (unsigned long long)c.lists,
                (unsigned long long)c.errors);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "discovery: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
