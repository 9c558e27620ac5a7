#include "idl/dds_entity.h"

namespace zonesim::dds {

DdsError::DdsError(const std::string& what, dds_return_t rc)
    : std::runtime_error(what + ": " + dds_strretcode(rc)), rc_(rc) {}

dds_return_t check(dds_return_t rc, const char* what) {
  if (rc < 0) throw DdsError(what, rc);
  return rc;
}

void Entity::reset() {
  if (handle_ > 0) dds_delete(handle_);
  handle_ = 0;
}

Entity makeParticipant(dds_domainid_t domain) {
  return Entity(check(dds_create_participant(domain, nullptr, nullptr), "dds_create_participant"));
}

Entity makeTopic(dds_entity_t participant, const dds_topic_descriptor_t* desc,
                 const std::string& name, const dds_qos_t* qos) {
  return Entity(check(dds_create_topic(participant, desc, name.c_str(), qos, nullptr),
                      "dds_create_topic"));
}

namespace {
dds_qos_t* partitionQos(const std::string& partition) {
  dds_qos_t* qos = dds_create_qos();
  if (!partition.empty()) dds_qset_partition1(qos, partition.c_str());
  return qos;
}
}  // namespace

PartitionWriter makePartitionWriter(dds_entity_t participant, dds_entity_t topic,
                                    const std::string& partition, const dds_qos_t* qos,
                                    const dds_listener_t* listener) {
  dds_qos_t* pqos = partitionQos(partition);
  Entity publisher(dds_create_publisher(participant, pqos, nullptr));
  dds_delete_qos(pqos);
  check(publisher.get(), "dds_create_publisher");
  Entity writer(
      check(dds_create_writer(publisher.get(), topic, qos, listener), "dds_create_writer"));
  return {std::move(publisher), std::move(writer)};
}

PartitionReader makePartitionReader(dds_entity_t participant, dds_entity_t topic,
                                    const std::string& partition, const dds_qos_t* qos) {
  dds_qos_t* sqos = partitionQos(partition);
  Entity subscriber(dds_create_subscriber(participant, sqos, nullptr));
  dds_delete_qos(sqos);
  check(subscriber.get(), "dds_create_subscriber");
  Entity reader(check(dds_create_reader(subscriber.get(), topic, qos, nullptr), "dds_create_reader"));
  return {std::move(subscriber), std::move(reader)};
}

std::string cellPartition(int ix, int iz) {
  return "c." + std::to_string(ix) + "." + std::to_string(iz);
}

std::string zonePartition(int rank) { return "z." + std::to_string(rank); }

}  // namespace zonesim::dds
