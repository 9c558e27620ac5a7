#pragma once
// A real Gateway on loopback UDP and a private DDS domain, with the zones' side emulated: the
// base of the tests that play one client against it. The gateway runs on its own thread from
// startGateway() until the test ends.

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>
#include <utility>

#include "gateway/gateway.h"
#include "gateway_fixture.h"

namespace zonesim::gateway {

class LoopbackGatewayTest : public ::testing::Test {
 protected:
  /// Builds the gateway from cfg (given a private domain and gateway id, and one zone to
  /// wait for) and the zone emulator on the same domain.
  void openGateway(GatewayConfig cfg) {
    int domain = testing::privateDdsDomain();
    cfg.dds_domain = domain;
    cfg.gateway_id = testing::privateGatewayId();
    cfg.expected_zones = 1;
    cfg_ = cfg;
    gateway_ = std::make_unique<Gateway>(cfg);
    zone_ = std::make_unique<testing::ZoneEmulator>(domain, cfg.scene, cfg.gateway_id);
    gateway_addr_ = Endpoint::loopback(gateway_->port());
  }
  /// Ends the gateway, sessions and all, and starts a new one of the same id on the same domain
  /// and another port, as a supervisor restarts a dead one; the zone emulator stays.
  void restartGateway() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    gateway_.reset();
    stop_ = false;
    gateway_ = std::make_unique<Gateway>(cfg_);
    gateway_addr_ = Endpoint::loopback(gateway_->port());
    startGateway();
  }
  void startGateway() {
    thread_ = std::thread([this] { gateway_->run(stop_); });
  }
  void TearDown() override {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }

  GatewayConfig cfg_;
  std::unique_ptr<Gateway> gateway_;
  std::unique_ptr<testing::ZoneEmulator> zone_;
  Endpoint gateway_addr_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace zonesim::gateway
