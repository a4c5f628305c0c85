#include "bridge_runner.h"

#include <chrono>

#include <fmt/format.h>
#include <ros/serialization.h>
#include <spdlog/spdlog.h>

namespace hubrt::hubbridge {
namespace {

dds::Qos qos_of(const BridgeConfig& config) {
  dds::Qos qos = dds::Qos::ros2_default(config.depth);
  if (config.reliability == Reliability::kBestEffort) qos.best_effort();
  return qos;
}

std::string describe(const BridgeConfig& c) {
  return c.direction == Direction::kRos1ToDds ? fmt::format("ROS 1 {} -> DDS {}", c.ros1_topic, c.dds_topic)
                                              : fmt::format("DDS {} -> ROS 1 {}", c.dds_topic, c.ros1_topic);
}

void remember_problem(Bridge& bridge, const std::string& problem) {
  const std::lock_guard lock(bridge.problem_mutex);
  if (bridge.last_problem != problem) spdlog::warn("{}: {}", describe(bridge.config), problem);
  bridge.last_problem = problem;
}

}  // namespace

std::int64_t monotonic_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

Expected<std::unique_ptr<BridgeRunner>> BridgeRunner::create(const BridgeFile& file,
                                                             const ros1::Messages& messages,
                                                             dds::Participant& participant) {
  std::unique_ptr<BridgeRunner> runner(new BridgeRunner());
  runner->messages_ = &messages;
  for (const BridgeConfig& config : file.bridges) {
    auto type = bridged_type(config.type, messages);
    if (!type) {
      return make_error(type.error().code,
                        fmt::format("bridge {}: {}", describe(config), type.error().message));
    }
    auto bridge = std::make_unique<Bridge>();
    bridge->config = config;
    bridge->type = *type;
    const dds::Qos qos = qos_of(config);
    auto topic = dds::UntypedTopic::create(participant, *type->type->descriptor, config.dds_topic, qos);
    if (!topic)
      return make_error(topic.error().code,
                        fmt::format("bridge {}: {}", describe(config), topic.error().message));
    bridge->topic.emplace(std::move(*topic));
    if (config.direction == Direction::kRos1ToDds) {
      auto writer = dds::UntypedWriter::create(participant, *bridge->topic, qos);
      if (!writer) return std::move(writer).error();
      bridge->writer.emplace(std::move(*writer));
      bridge->inbound = std::make_unique<Ros1Inbound>(*type, messages);
    } else {
      BridgeRunner* self = runner.get();
      auto reader = dds::UntypedReader::create(participant, *bridge->topic, qos, [self] {
        self->dds_data_ = true;
        self->wake_.notify_one();
      });
      if (!reader) return std::move(reader).error();
      bridge->reader.emplace(std::move(*reader));
      bridge->dds_sample.assign(type->type->size, 0);
    }
    spdlog::info("bridge {} ({}, md5sum {})", describe(config), type->ros1_name, type->md5sum);
    runner->bridges_.push_back(std::move(bridge));
  }
  return runner;
}

BridgeRunner::~BridgeRunner() {
  shutdown_ros1();
  for (auto& bridge : bridges_) {
    bridge->reader.reset();  // waits for a running data-available callback
    if (!bridge->dds_sample.empty())
      dds_sample_free(bridge->dds_sample.data(), bridge->type.type->descriptor, DDS_FREE_CONTENTS);
  }
}

void BridgeRunner::shutdown_ros1() {
  for (auto& bridge : bridges_) {
    bridge->subscriber.shutdown();
    bridge->publisher.shutdown();
  }
}

void BridgeRunner::register_ros1(ros::NodeHandle& node) {
  // Shut down first: roscpp keeps one registration per topic and node (TopicManager::subscribe /
  // advertise call registerSubscriber / registerPublisher on the master).
  shutdown_ros1();
  for (auto& bridge_ptr : bridges_) {
    Bridge& bridge = *bridge_ptr;
    const auto queue = static_cast<std::uint32_t>(bridge.config.depth);
    if (bridge.config.direction == Direction::kRos1ToDds) {
      subscribe(bridge, node);
    } else {
      topic_tools::ShapeShifter shape;
      shape.morph(bridge.type.md5sum, bridge.type.ros1_name, bridge.type.definition,
                  bridge.config.latch ? "true" : "false");
      bridge.publisher = shape.advertise(node, bridge.config.ros1_topic, queue, bridge.config.latch);
    }
  }
}

std::vector<SyncedEndpoint> BridgeRunner::endpoints() const {
  std::vector<SyncedEndpoint> out;
  for (const auto& bridge : bridges_) {
    out.push_back({bridge->config.ros1_topic, bridge->type.ros1_name,
                   bridge->config.direction == Direction::kRos1ToDds});
  }
  return out;
}

std::vector<std::vector<std::string>> BridgeRunner::heard_since(std::int64_t since_ns) const {
  std::vector<std::vector<std::string>> out;
  for (const auto& bridge : bridges_) out.push_back(bridge->heard.since(since_ns));
  return out;
}

void BridgeRunner::subscribe(Bridge& bridge, ros::NodeHandle& node) {
  bridge.subscriber.shutdown();
  // ShapeShifter subscribes with md5sum "*", so roscpp connects to any publisher of the topic and
  // hands over the raw bytes with the publisher's connection header (topic_tools/shape_shifter.h);
  // the type check is ours (check_publisher). Strict: the expected md5sum and type instead.
  ros::SubscribeOptions options;
  options.initByFullCallbackType<const ros::MessageEvent<topic_tools::ShapeShifter const>&>(
      bridge.config.ros1_topic, static_cast<std::uint32_t>(bridge.config.depth),
      [this, &bridge](const ros::MessageEvent<topic_tools::ShapeShifter const>& event) {
        on_ros1_message(bridge, event);
      });
  if (bridge.strict) {
    options.md5sum = bridge.type.md5sum;
    options.datatype = bridge.type.ros1_name;
  }
  if (bridge.config.reliability == Reliability::kBestEffort)
    options.transport_hints = ros::TransportHints().udp();
  bridge.subscriber = node.subscribe(options);
}

void BridgeRunner::resubscribe_refused(ros::NodeHandle& node) {
  for (auto& bridge : bridges_) {
    if (bridge->resubscribe.exchange(false)) {
      spdlog::info("{}: subscribing again with md5sum {} only", describe(bridge->config),
                   bridge->type.md5sum);
      subscribe(*bridge, node);
    }
  }
}

void BridgeRunner::on_ros1_message(Bridge& bridge,
                                   const ros::MessageEvent<topic_tools::ShapeShifter const>& event) {
  const auto& message = *event.getConstMessage();
  const auto header = event.getConnectionHeaderPtr();
  const auto field = [&](const char* key) {
    if (!header) return std::string();
    const auto it = header->find(key);
    return it == header->end() ? std::string() : it->second;
  };
  const std::string problem = bridge.inbound->check_publisher(
      event.getPublisherName(), message.getDataType(), message.getMD5Sum(), field("message_definition"));
  if (!problem.empty()) {
    ++bridge.counters.type_errors;
    remember_problem(bridge, problem);
    if (!bridge.strict.exchange(true)) bridge.resubscribe = true;
    return;
  }
  bridge.heard.heard(event.getPublisherName(), monotonic_ns());
  std::vector<std::uint8_t> bytes(message.size());
  ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  message.write(stream);
  std::string why;
  switch (bridge.inbound->take(bytes, &why)) {
    case Verdict::kForward:
      if (bridge.writer->write(bridge.inbound->sample()).is_ok()) {
        ++bridge.counters.forwarded;
        bridge.counters.last_forward_ns = monotonic_ns();
      } else {
        ++bridge.counters.write_errors;
      }
      return;
    case Verdict::kOverBound:
      ++bridge.counters.dropped;
      bridge.counters.last_drop_ns = monotonic_ns();
      break;
    case Verdict::kTypeError:
      ++bridge.counters.type_errors;
      break;
    case Verdict::kStale:
      ++bridge.counters.stale;
      break;
  }
  remember_problem(bridge, fmt::format("dropped a message from {}: {}", event.getPublisherName(), why));
}

void BridgeRunner::forward_dds(Duration timeout) {
  {
    std::unique_lock lock(wake_mutex_);
    wake_.wait_for(lock, timeout, [this] { return dds_data_.load(); });
    dds_data_ = false;
  }
  for (auto& bridge_ptr : bridges_) {
    Bridge& bridge = *bridge_ptr;
    if (!bridge.reader) continue;
    while (true) {
      auto taken = bridge.reader->take_next(bridge.dds_sample.data());
      if (!taken.is_ok() || !taken.value()) break;
      to_ros1(bridge.type, bridge.dds_sample.data(), bridge.ros1_bytes);
      topic_tools::ShapeShifter shape;
      shape.morph(bridge.type.md5sum, bridge.type.ros1_name, bridge.type.definition,
                  bridge.config.latch ? "true" : "false");
      ros::serialization::IStream stream(bridge.ros1_bytes.data(),
                                         static_cast<std::uint32_t>(bridge.ros1_bytes.size()));
      shape.read(stream);
      if (bridge.publisher) {
        bridge.publisher.publish(shape);
        ++bridge.counters.forwarded;
        bridge.counters.last_forward_ns = monotonic_ns();
      }
    }
  }
}

}  // namespace hubrt::hubbridge
