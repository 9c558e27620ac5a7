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
/// Commands that must not be dropped (inputs, spawn requests, ownership events): KEEP_ALL.
Qos reliableKeepAllQos();
/// Gateway load reports: only the newest counts, and a lobby started later gets it at once
/// (reliable, TRANSIENT_LOCAL, KEEP_LAST 1 per gateway).
Qos gatewayLoadQos();

}  // namespace zonesim::dds
