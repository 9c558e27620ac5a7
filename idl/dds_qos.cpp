#include "idl/dds_qos.h"

namespace zonesim::dds {

namespace {
constexpr dds_duration_t kMaxBlocking = DDS_MSECS(100);
}

Qos cellUpdateQos() {
  Qos q(dds_create_qos());
  dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, kMaxBlocking);
  dds_qset_durability(q.get(), DDS_DURABILITY_VOLATILE);
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, 16);
  return q;
}

Qos cellKeyframeQos() {
  Qos q(dds_create_qos());
  dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, kMaxBlocking);
  dds_qset_durability(q.get(), DDS_DURABILITY_TRANSIENT_LOCAL);
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, 1);
  return q;
}

Qos reliableKeepAllQos() {
  Qos q(dds_create_qos());
  dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, kMaxBlocking);
  dds_qset_durability(q.get(), DDS_DURABILITY_VOLATILE);
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_ALL, 0);
  return q;
}

Qos playerInputQos() {
  Qos q(dds_create_qos());
  dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, kMaxBlocking);
  dds_qset_durability(q.get(), DDS_DURABILITY_VOLATILE);
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, kInputDepth);
  return q;
}

Qos gatewayLoadQos() {
  Qos q(dds_create_qos());
  dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, kMaxBlocking);
  dds_qset_durability(q.get(), DDS_DURABILITY_TRANSIENT_LOCAL);
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, 1);
  return q;
}

}  // namespace zonesim::dds
