#pragma once
// The QoS of each zonesim topic, in one place so writers and readers always agree.

#include <dds/dds.h>

#include <memory>

namespace zonesim::dds {

struct QosDeleter {
  void operator()(dds_qos_t* q) const { dds_delete_qos(q); }
};
using Qos = std::unique_ptr<dds_qos_t, QosDeleter>;

/// Per-cell update batches: reliable, volatile, a short history per (cell, zone) instance.
Qos cellUpdateQos();
/// Per-cell keyframes: reliable, TRANSIENT_LOCAL, KEEP_LAST 1, so a new reader starts complete.
Qos cellKeyframeQos();
/// Commands that must not be dropped (spawn requests, ownership events; inputs at readers):
/// KEEP_ALL.
Qos reliableKeepAllQos();
/// The gateway's input writers: reliable, KEEP_LAST kInputDepth per player. A zone that died
/// stays matched until its lease ends; a KEEP_ALL writer would fill its history for it and
/// block the gateway 100 ms a write, while this one keeps the newest and never blocks (the
/// gateway resends what a restarted zone lacks, gateway/gateway_epochs.cpp).
Qos playerInputQos();
inline constexpr int kInputDepth = 64;
/// Gateway load reports: only the newest counts, and a lobby started later gets it at once
/// (reliable, TRANSIENT_LOCAL, KEEP_LAST 1 per gateway).
Qos gatewayLoadQos();

}  // namespace zonesim::dds
