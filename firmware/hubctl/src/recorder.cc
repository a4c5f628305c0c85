#include "recorder.h"

#include <algorithm>

#include <fmt/format.h>

#include "hubrt/mcap/ros2_qos_yaml.h"

namespace hubrt::hubctl {
namespace {

std::uint64_t mcap_time(WallTime t) noexcept {
  return t.ns_since_epoch < 0 ? 0 : static_cast<std::uint64_t>(t.ns_since_epoch);
}

}  // namespace

Expected<Recorder> Recorder::create(RecorderOptions options) {
  auto writer = mcap::SplitWriter::create(options.path, options.writer, options.split);
  if (!writer) return std::move(writer).error();
  return Recorder(std::move(options), std::move(*writer));
}

Expected<std::uint16_t> Recorder::channel_of(const TapTopic& topic) {
  if (const auto known = channels_.find(topic.ros_name); known != channels_.end()) return known->second;
  if (topic.schema.empty()) {
    return make_error(ErrorCode::kNotFound,
                      fmt::format("{} ({}): no .msg definition", topic.ros_name, topic.type_name));
  }
  auto schema = schemas_.find(topic.type_name);
  if (schema == schemas_.end()) {
    // One Schema per type, named as ROS 2 names it, its data the ros2msg text (MCAP spec
    // registry.md, "ros2msg"; rosbag2_storage_mcap, MCAPStorage::create_topic).
    auto id = writer_.add_schema({0, topic.type_name, "ros2msg", topic.schema});
    if (!id) return std::move(id).error();
    schema = schemas_.emplace(topic.type_name, *id).first;
  }
  // The QoS as the writers offer it when the topic's first sample is taken: the channel's, as
  // rosbag2 records the offers of the publishers it found when it subscribed.
  mcap::Channel channel{0,
                        schema->second,
                        topic.ros_name,
                        "cdr",
                        {{"offered_qos_profiles", mcap::offered_qos_yaml(topic.offered)}}};
  if (!topic.station.empty()) {
    // A plant's station (plant_tap.h): the topic's name carries the station's in front; its DDS
    // domain and its name on the wire stay in the channel's metadata.
    channel.metadata.emplace("hubrt.station", topic.station);
    channel.metadata.emplace("hubrt.dds_domain_id", std::to_string(topic.domain_id));
    channel.metadata.emplace("hubrt.wire_topic", topic.ros_name.substr(topic.station.size() + 1));
  }
  auto id = writer_.add_channel(channel);
  if (!id) return std::move(id).error();
  channels_.emplace(topic.ros_name, *id);
  return *id;
}

Expected<void> Recorder::take(const TapEvent& event, std::chrono::steady_clock::time_point now) {
  if (event.kind != TapEvent::Kind::kSample) return {};
  const TapSample& sample = *event.sample;
  const TapTopic& topic = *sample.topic;
  if (unrecordable_.count(topic.ros_name) != 0) return {};
  auto channel = channel_of(topic);
  if (!channel) {
    if (channel.error().code != ErrorCode::kNotFound) return std::move(channel).error();
    unrecordable_.emplace(topic.ros_name, topic.type_name);
    return {};
  }
  mcap::Message message;
  message.channel_id = *channel;
  // MCAP's sequence is a uint32 "message counter to detect gaps": the tap's count per topic.
  message.sequence = static_cast<std::uint32_t>(sample.sequence);
  message.log_time = mcap_time(sample.receive_time);
  // "If not available, must be set to the log time" (spec, "Message").
  message.publish_time =
      sample.source_time.ns_since_epoch > 0 ? mcap_time(sample.source_time) : message.log_time;
  message.data = sample.cdr;
  if (auto written = writer_.write(message); !written) return written;
  if (!chunk_open_) {
    chunk_open_ = true;
    chunk_opened_ = now;
  }
  return tick(now);
}

Expected<void> Recorder::tick(std::chrono::steady_clock::time_point now) {
  if (!chunk_open_ || now - chunk_opened_ < options_.chunk_period) return {};
  chunk_open_ = false;
  return writer_.close_chunk();
}

Expected<void> Recorder::finish() {
  return writer_.finish();
}

RecorderProgress Recorder::progress() const {
  RecorderProgress p;
  p.messages = writer_.messages();
  p.bytes = writer_.bytes();
  p.topics = channels_.size();
  p.files = writer_.files();
  return p;
}

}  // namespace hubrt::hubctl
