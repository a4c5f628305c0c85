// A DDS topic: a name on the wire bound to a type descriptor.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <dds/dds.h>

#include "hubrt/base/status.h"
#include "hubrt/dds/entity.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/qos.h"
#include "hubrt/dds/topic_type.h"

namespace hubrt::dds {

// A topic for a type known by its descriptor only (hubctl handles arbitrary known types).
// Move-only; dds_delete() on destruction. Thread-safety: as Participant.
class UntypedTopic {
 public:
  // Topic for ROS 2 topic `ros_name` (e.g. "/dock/command" -> DDS "rt/dock/command").
  // Precondition: `descriptor` outlives the topic (generated descriptors are static).
  // Errors: kInvalidArgument for an invalid ROS name (see validate_ros_topic_name); Cyclone's
  // refusal as "create topic 'rt/...' of type '...' in domain N: DDS_RETCODE_...".
  static Expected<UntypedTopic> create(const Participant& participant,
                                       const dds_topic_descriptor_t& descriptor, std::string_view ros_name,
                                       const Qos& qos = Qos::ros2_default());
  // Topic with a raw DDS topic name, used as given (for non-ROS topics and tools).
  // Errors: Cyclone's refusal, as above.
  static Expected<UntypedTopic> create_with_dds_name(const Participant& participant,
                                                     const dds_topic_descriptor_t& descriptor,
                                                     std::string_view dds_name,
                                                     const Qos& qos = Qos::ros2_default());

  [[nodiscard]] dds_entity_t handle() const noexcept { return handle_.get(); }
  [[nodiscard]] const dds_topic_descriptor_t& descriptor() const noexcept { return *descriptor_; }
  // The DDS topic name, e.g. "rt/dock/command".
  [[nodiscard]] const std::string& dds_name() const noexcept { return dds_name_; }
  [[nodiscard]] std::uint32_t domain_id() const noexcept { return domain_id_; }

 private:
  UntypedTopic(EntityHandle handle, const dds_topic_descriptor_t& descriptor, std::string dds_name,
               std::uint32_t domain_id) noexcept
      : handle_(std::move(handle)),
        descriptor_(&descriptor),
        dds_name_(std::move(dds_name)),
        domain_id_(domain_id) {}

  EntityHandle handle_;
  const dds_topic_descriptor_t* descriptor_;
  std::string dds_name_;
  std::uint32_t domain_id_;
};

// Checks that a generated C type matches its registered descriptor (sizeof(T) == m_size), which
// catches a HUBRT_DDS_TOPIC_TYPE that pairs a struct with the wrong descriptor.
// Errors: kInvalidArgument naming the descriptor's type name and both sizes.
Expected<void> check_type_size(const dds_topic_descriptor_t& descriptor, std::size_t type_size);

// A topic of generated type T (registered with HUBRT_DDS_TOPIC_TYPE). Move-only.
template <TopicType T>
class Topic {
 public:
  // As UntypedTopic::create; also fails (kInvalidArgument) if sizeof(T) differs from the
  // descriptor's m_size.
  static Expected<Topic> create(const Participant& participant, std::string_view ros_name,
                                const Qos& qos = Qos::ros2_default()) {
    return wrap(participant, ros_name, qos, &UntypedTopic::create);
  }
  static Expected<Topic> create_with_dds_name(const Participant& participant, std::string_view dds_name,
                                              const Qos& qos = Qos::ros2_default()) {
    return wrap(participant, dds_name, qos, &UntypedTopic::create_with_dds_name);
  }

  [[nodiscard]] const UntypedTopic& untyped() const noexcept { return topic_; }
  [[nodiscard]] dds_entity_t handle() const noexcept { return topic_.handle(); }
  [[nodiscard]] const std::string& dds_name() const noexcept { return topic_.dds_name(); }

 private:
  explicit Topic(UntypedTopic topic) noexcept : topic_(std::move(topic)) {}

  template <class Factory>
  static Expected<Topic> wrap(const Participant& participant, std::string_view name, const Qos& qos,
                              Factory factory) {
    const dds_topic_descriptor_t& descriptor = TopicTraits<T>::descriptor();
    if (auto size_ok = check_type_size(descriptor, sizeof(T)); !size_ok) return std::move(size_ok).error();
    auto topic = factory(participant, descriptor, name, qos);
    if (!topic) return std::move(topic).error();
    return Topic(std::move(*topic));
  }

  UntypedTopic topic_;
};

}  // namespace hubrt::dds
