// A Fast DDS (eProsima, Debian's libfastrtps 2.9) participant pinned to loopback, configured the
// way it interoperates with hubd's Cyclone DDS in a test's own domain (docs/interop.md).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "hubrt/base/status.h"

namespace hubrt::interop {

// The participant QoS: Fast DDS's own defaults (get_default_participant_qos()), then
//  - only a UDPv4 transport whitelisted to 127.0.0.1 (no shared memory: Cyclone does not speak
//    Fast DDS's SHM transport, and no other interface: the test stays on loopback);
//  - 127.0.0.1 as the unicast initial peer, probed for participant indices 0..31 (a test's
//    domain holds far fewer participants; Fast DDS's default range is only 4).
// Which settings are needed and why: docs/interop.md.
eprosima::fastdds::dds::DomainParticipantQos loopback_participant_qos(const std::string& name);

// Participant properties (name, value), e.g. Fast DDS's "dds.sec.*" security settings.
using ParticipantProperties = std::vector<std::pair<std::string, std::string>>;

// ROS 2's default QoS for topics (reliable, volatile, keep last 10), as hubd uses them.
eprosima::fastdds::dds::DataWriterQos ros2_default_writer_qos();
eprosima::fastdds::dds::DataReaderQos ros2_default_reader_qos();

// A Fast DDS participant on loopback in one domain, with one publisher and one subscriber.
// Deleting it deletes every entity created through it. Not copyable, not movable (Fast DDS
// keeps pointers to its entities). Thread-safety: Fast DDS entities are thread-safe; create
// entities from one thread.
class LoopbackParticipant {
 public:
  // `properties` are added to the participant QoS (e.g. the security plugins' settings).
  // Errors: kUnavailable when Fast DDS refuses the participant (no UDP socket, a security
  // plugin that cannot load its certificates or documents: Fast DDS logs why).
  static Expected<std::unique_ptr<LoopbackParticipant>> create(std::uint32_t domain_id,
                                                               const std::string& name,
                                                               const ParticipantProperties& properties = {});
  ~LoopbackParticipant();
  LoopbackParticipant(const LoopbackParticipant&) = delete;
  LoopbackParticipant& operator=(const LoopbackParticipant&) = delete;

  // A writer / reader on DDS topic `dds_topic` (the ROS 2 name with its "rt" prefix) of the
  // registered type `type` (a TypeSupport made from a fastddsgen PubSubType; registered here on
  // first use, under its ROS 2 name). Errors: kInvalidArgument when Fast DDS refuses the
  // topic or the entity; the returned pointer is owned by the participant.
  Expected<eprosima::fastdds::dds::DataWriter*> create_writer(const std::string& dds_topic,
                                                              eprosima::fastdds::dds::TypeSupport type);
  Expected<eprosima::fastdds::dds::DataReader*> create_reader(const std::string& dds_topic,
                                                              eprosima::fastdds::dds::TypeSupport type);

 private:
  LoopbackParticipant() = default;
  Expected<eprosima::fastdds::dds::Topic*> topic(const std::string& dds_topic,
                                                 eprosima::fastdds::dds::TypeSupport& type);

  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
};

}  // namespace hubrt::interop
