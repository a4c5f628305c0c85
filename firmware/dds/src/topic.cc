#include "hubrt/dds/topic.h"

#include "hubrt/dds/retcode.h"
#include "hubrt/dds/ros_names.h"

namespace hubrt::dds {
namespace {

// The descriptor as the topic is created from: without the XTypes type information idlc put in
// it, so that our endpoints announce type names only, as rmw_cyclonedds' do on ROS 2 Humble
// (serdata.cpp, sertype_rmw_ops: "not yet providing type discovery").
//
// Why: with type information, Cyclone 0.10.2 resolves a local topic's type against the proxy
// endpoints that announced it, and uses those endpoints after it has let go of the entity index
// (ddsi_typelib.c, ddsi_type_ref_local: ddsi_type_get_gpe_matches collects them, the matching runs
// after typelib_lock is released and the thread is asleep). An endpoint its peer deleted in
// between is read after it was freed: CI's ASan build met it in `hubctl record`, whose tap creates
// a topic as soon as it discovers a hub's writer. A topic without type information returns from
// ddsi_type_ref_local at once, and peers match it by type name. Cyclone copies what it keeps of the
// descriptor (ddsi_sertype_default_init), so the copy may go when the topic is made.
dds_topic_descriptor_t without_type_information(const dds_topic_descriptor_t& descriptor) {
  // The descriptor's members are const: it is built whole, member by member.
  return dds_topic_descriptor_t{
      .m_size = descriptor.m_size,
      .m_align = descriptor.m_align,
      .m_flagset = descriptor.m_flagset & ~static_cast<std::uint32_t>(DDS_TOPIC_XTYPES_METADATA),
      .m_nkeys = descriptor.m_nkeys,
      .m_typename = descriptor.m_typename,
      .m_keys = descriptor.m_keys,
      .m_nops = descriptor.m_nops,
      .m_ops = descriptor.m_ops,
      .m_meta = descriptor.m_meta,
      .type_information = {},
      .type_mapping = {},
      .restrict_data_representation = descriptor.restrict_data_representation,
  };
}

}  // namespace

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
  const dds_topic_descriptor_t plain = without_type_information(descriptor);
  const dds_entity_t handle =
      dds_create_topic(participant.handle(), &plain, name.c_str(), qos.get(), nullptr);
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
