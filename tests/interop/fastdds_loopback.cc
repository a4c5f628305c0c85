#include "fastdds_loopback.h"

#include <memory>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

namespace hubrt::interop {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

namespace {

// Fast DDS probes the initial peer at the ports of this many participant indices: a test's
// private domain holds a few participants (Cyclone's loopback configuration,
// dds::loopback_config_xml, would admit kLoopbackParticipantsPerHost).
constexpr std::uint32_t kPeerIndices = 32;

}  // namespace

fdds::DomainParticipantQos loopback_participant_qos(const std::string& name) {
  // Starting from the factory's defaults matters: a default-constructed DomainParticipantQos
  // differs from them (Fast DDS reads its XML profile and environment into the factory's).
  fdds::DomainParticipantQos qos =
      fdds::DomainParticipantFactory::get_instance()->get_default_participant_qos();
  qos.name(name);
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->interfaceWhiteList.emplace_back("127.0.0.1");
  udp->maxInitialPeersRange = kPeerIndices;
  qos.transport().use_builtin_transports = false;  // the builtins add shared memory
  qos.transport().user_transports.push_back(udp);
  Locator_t peer;
  peer.kind = LOCATOR_KIND_UDPv4;
  IPLocator::setIPv4(peer, 127, 0, 0, 1);
  qos.wire_protocol().builtin.initialPeersList.push_back(peer);
  return qos;
}

fdds::DataWriterQos ros2_default_writer_qos() {
  fdds::DataWriterQos qos = fdds::DATAWRITER_QOS_DEFAULT;
  qos.reliability().kind = fdds::RELIABLE_RELIABILITY_QOS;
  qos.durability().kind = fdds::VOLATILE_DURABILITY_QOS;
  qos.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
  qos.history().depth = 10;
  // Fast DDS turns data sharing on by itself for bounded types (ours): shared memory files in
  // /dev/shm that a crashed test leaves behind, for a feature Cyclone does not speak.
  qos.data_sharing().off();
  return qos;
}

fdds::DataReaderQos ros2_default_reader_qos() {
  fdds::DataReaderQos qos = fdds::DATAREADER_QOS_DEFAULT;
  qos.reliability().kind = fdds::RELIABLE_RELIABILITY_QOS;
  qos.durability().kind = fdds::VOLATILE_DURABILITY_QOS;
  qos.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
  qos.history().depth = 10;
  qos.data_sharing().off();  // as for the writer
  return qos;
}

Expected<std::unique_ptr<LoopbackParticipant>> LoopbackParticipant::create(
    std::uint32_t domain_id, const std::string& name, const ParticipantProperties& properties) {
  std::unique_ptr<LoopbackParticipant> self(new LoopbackParticipant());
  auto* factory = fdds::DomainParticipantFactory::get_instance();
  fdds::DomainParticipantQos qos = loopback_participant_qos(name);
  for (const auto& [key, value] : properties) qos.properties().properties().emplace_back(key, value);
  self->participant_ = factory->create_participant(static_cast<fdds::DomainId_t>(domain_id), qos);
  if (self->participant_ == nullptr) {
    return make_error(ErrorCode::kUnavailable,
                      "Fast DDS refused the participant in domain " + std::to_string(domain_id));
  }
  self->publisher_ = self->participant_->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  self->subscriber_ = self->participant_->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  if (self->publisher_ == nullptr || self->subscriber_ == nullptr) {
    return make_error(ErrorCode::kUnavailable, "Fast DDS refused a publisher or subscriber");
  }
  return self;
}

LoopbackParticipant::~LoopbackParticipant() {
  if (participant_ == nullptr) return;
  (void)participant_->delete_contained_entities();
  (void)fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

Expected<fdds::Topic*> LoopbackParticipant::topic(const std::string& dds_topic, fdds::TypeSupport& type) {
  if (participant_->find_type(type.get_type_name()).empty()) {
    if (type.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
      return make_error(ErrorCode::kInvalidArgument, "Fast DDS refused the type " + type.get_type_name());
    }
  }
  if (auto* existing = dynamic_cast<fdds::Topic*>(participant_->lookup_topicdescription(dds_topic))) {
    return existing;
  }
  fdds::Topic* created = participant_->create_topic(dds_topic, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  if (created == nullptr) {
    return make_error(ErrorCode::kInvalidArgument,
                      "Fast DDS refused the topic " + dds_topic + " of type " + type.get_type_name());
  }
  return created;
}

Expected<fdds::DataWriter*> LoopbackParticipant::create_writer(const std::string& dds_topic,
                                                               fdds::TypeSupport type) {
  auto topic_entity = topic(dds_topic, type);
  if (!topic_entity) return std::move(topic_entity).error();
  fdds::DataWriter* writer = publisher_->create_datawriter(*topic_entity, ros2_default_writer_qos());
  if (writer == nullptr)
    return make_error(ErrorCode::kInvalidArgument, "Fast DDS refused a writer on " + dds_topic);
  return writer;
}

Expected<fdds::DataReader*> LoopbackParticipant::create_reader(const std::string& dds_topic,
                                                               fdds::TypeSupport type) {
  auto topic_entity = topic(dds_topic, type);
  if (!topic_entity) return std::move(topic_entity).error();
  fdds::DataReader* reader = subscriber_->create_datareader(*topic_entity, ros2_default_reader_qos());
  if (reader == nullptr)
    return make_error(ErrorCode::kInvalidArgument, "Fast DDS refused a reader on " + dds_topic);
  return reader;
}

}  // namespace hubrt::interop
