#include "hubrt/dds/topic.h"

#include "hubrt/dds/retcode.h"
#include "hubrt/dds/ros_names.h"

namespace hubrt::dds {

Expected<UntypedTopic> UntypedTopic::create(const Participant& participant,
                                            const dds_topic_descriptor_t& descriptor,
                                            std::string_view ros_name, const Qos& qos) {
  auto dds_name = ros_to_dds_topic(ros_name);
  if (!dds_name) return std::move(dds_name).error();
  return create_with_dds_name(participant, descriptor, *dds_name, qos);
}

Expected<UntypedTopic> UntypedTopic::create_with_dds_name(const Participant& participant,
                                                          const dds_topic_descriptor_t& descriptor,
                                                          std::string_view dds_name, const Qos& qos) {
  std::string name(dds_name);
  const dds_entity_t handle =
      dds_create_topic(participant.handle(), &descriptor, name.c_str(), qos.get(), nullptr);
  if (handle < 0) {
    return dds_error(handle, "create topic '" + name + "' of type '" + descriptor.m_typename +
                                 "' in domain " + std::to_string(participant.domain_id()));
  }
  return UntypedTopic(EntityHandle(handle), descriptor, std::move(name), participant.domain_id());
}

Expected<void> check_type_size(const dds_topic_descriptor_t& descriptor, std::size_t type_size) {
  if (descriptor.m_size == type_size) return {};
  return make_error(ErrorCode::kInvalidArgument, "C type registered for '" +
                                                     std::string(descriptor.m_typename) + "' has size " +
                                                     std::to_string(type_size) + " but its descriptor says " +
                                                     std::to_string(descriptor.m_size) +
                                                     ": HUBRT_DDS_TOPIC_TYPE pairs the wrong descriptor");
}

}  // namespace hubrt::dds
