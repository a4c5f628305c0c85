// The States of one topic as the suite receives them: a reader woken by a waitset, each State
// stamped with its arrival time on the steady clock and kept, in order, as an Observation.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/read_condition.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/waitset.h"
#include "hubrt/msgs/type_info.h"

#include "conformance_checks.h"
#include "sample_decoder.h"

namespace hubrt::hubctl {

// The steady clock in seconds, the time base of Observation::arrival_s.
double steady_seconds() noexcept;

// The wall clock in seconds, the time base of a DDS source timestamp and of a State's stamp.
double wall_seconds() noexcept;

// Turns a State (as JSON, from SampleDecoder, with the common State fields) into an Observation.
Observation observe(nlohmann::ordered_json state, double arrival_s);

// Move-only. Thread-safety: use from one thread; creation may happen on another before that.
class StateStream {
 public:
  // Subscribes to `ros_topic` (ROS 2 default QoS, as a planner would). Errors: the DDS entity that
  // could not be created, with Cyclone's reason.
  static Expected<StateStream> open(const dds::Participant& participant, const std::string& ros_topic,
                                    const msgs::TypeInfo& type);

  // Waits until the hub's writer is matched; returns when that happened (steady seconds).
  // Errors: kTimeout naming the topic.
  Expected<double> wait_matched(double timeout_s);

  // Blocks until States arrive or `deadline_s` (steady seconds) passes, then appends every State
  // waiting. Returns how many were appended. Errors: Cyclone's code from waiting or taking.
  Result<std::size_t> pump(double deadline_s) noexcept;

  // Discards the States received so far, and those waiting in the reader (whose history holds
  // only the last few while nobody takes them), so that what follows is one unbroken sequence.
  // The first State ever received is still remembered.
  Result<std::size_t> restart() noexcept;

  [[nodiscard]] const std::vector<Observation>& log() const noexcept { return log_; }
  // Arrival time of the first State this stream ever received.
  [[nodiscard]] std::optional<double> first_arrival_s() const noexcept { return first_arrival_s_; }
  [[nodiscard]] const msgs::TypeInfo& type() const noexcept { return *type_; }

 private:
  StateStream(const msgs::TypeInfo& type, dds::UntypedTopic topic, dds::UntypedReader reader,
              dds::ReadCondition condition, dds::WaitSet waitset)
      : type_(&type),
        topic_(std::move(topic)),
        reader_(std::move(reader)),
        condition_(std::move(condition)),
        waitset_(std::move(waitset)),
        sample_(*type.descriptor),
        decoder_("hubctl conformance", reader_.topic_name()) {}

  const msgs::TypeInfo* type_;
  // Destroyed in reverse: the waitset before the condition, the reader before its topic.
  dds::UntypedTopic topic_;
  dds::UntypedReader reader_;
  dds::ReadCondition condition_;
  dds::WaitSet waitset_;
  dds::UntypedSample sample_;
  SampleDecoder decoder_;
  std::vector<Observation> log_;
  std::optional<double> first_arrival_s_;
};

}  // namespace hubrt::hubctl
