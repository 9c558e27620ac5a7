#pragma once
// RAII over Cyclone DDS entity handles, and helpers that create the entities zonesim uses.
// Errors come back as DdsError exceptions carrying dds_strretcode(); nothing here exits.

#include <dds/dds.h>

#include <stdexcept>
#include <string>
#include <utility>

namespace zonesim::dds {

/// A failed DDS call: what was attempted and Cyclone's return-code text.
class DdsError : public std::runtime_error {
 public:
  DdsError(const std::string& what, dds_return_t rc);
  dds_return_t code() const { return rc_; }

 private:
  dds_return_t rc_;
};

/// Throws DdsError when rc (or a handle) is negative; returns it otherwise.
dds_return_t check(dds_return_t rc, const char* what);

/// Owns one DDS entity; deleting it deletes its children (readers, writers) too.
class Entity {
 public:
  Entity() = default;
  explicit Entity(dds_entity_t handle) : handle_(handle) {}
  ~Entity() { reset(); }
  Entity(Entity&& other) noexcept : handle_(std::exchange(other.handle_, 0)) {}
  Entity& operator=(Entity&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, 0);
    }
    return *this;
  }
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;

  dds_entity_t get() const { return handle_; }
  explicit operator bool() const { return handle_ > 0; }
  void reset();

 private:
  dds_entity_t handle_ = 0;
};

/// A participant on the given domain (config from CYCLONEDDS_URI).
Entity makeParticipant(dds_domainid_t domain);

/// A topic of the given descriptor, with the topic-level QoS.
Entity makeTopic(dds_entity_t participant, const dds_topic_descriptor_t* desc,
                 const std::string& name, const dds_qos_t* qos);

/// A publisher restricted to one partition ("" = default partition), and a writer in it.
struct PartitionWriter {
  Entity publisher;
  Entity writer;
};
/// `listener`, when given, is set on the writer as it is created (no event is missed).
PartitionWriter makePartitionWriter(dds_entity_t participant, dds_entity_t topic,
                                    const std::string& partition, const dds_qos_t* qos,
                                    const dds_listener_t* listener = nullptr);

/// A subscriber restricted to one partition, and a reader in it. Partitions cannot change at
/// run time in Cyclone (DDS_RETCODE_UNSUPPORTED), so interest changes create and delete these.
struct PartitionReader {
  Entity subscriber;
  Entity reader;
};
PartitionReader makePartitionReader(dds_entity_t participant, dds_entity_t topic,
                                    const std::string& partition, const dds_qos_t* qos);

/// Name of the partition carrying interest cell (ix, iz).
std::string cellPartition(int ix, int iz);
/// Name of the partition carrying inputs for zone rank r.
std::string zonePartition(int rank);

}  // namespace zonesim::dds
