// One hubbridge process: its bridges' DDS readers and writers, their ROS 1 subscribers and
// publishers (roscpp, topic_tools::ShapeShifter so that no type is compiled in), and the watch on
// rosmaster that registers them again when the master restarts.
#pragma once

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <topic_tools/shape_shifter.h>

#include "hubrt/dds/participant.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"

#include "bridge_config.h"
#include "bridge_core.h"

namespace hubrt::hubbridge {

struct Bridge {
  BridgeConfig config;
  BridgedType type;
  BridgeCounters counters;
  std::optional<dds::UntypedTopic> topic;
  std::optional<dds::UntypedWriter> writer;  // ros1_to_dds
  std::optional<dds::UntypedReader> reader;  // dds_to_ros1
  std::unique_ptr<Ros1Inbound> inbound;      // ros1_to_dds
  ros::Subscriber subscriber;                // ros1_to_dds
  ros::Publisher publisher;                  // dds_to_ros1
  std::vector<std::uint8_t> dds_sample;      // dds_to_ros1: taken samples land here
  std::vector<std::uint8_t> ros1_bytes;      // dds_to_ros1: serialised for ROS 1
  std::string last_problem;                  // the last refusal, for /diagnostics
  // A roscpp 1.15 subscription with md5sum "*" takes the md5sum of the first publisher it hears
  // and asks every later one for it (seen in tests/ros1's mismatch test: the next, right
  // publisher refused with "topic types do not match"). After a publisher with another
  // definition was heard and named, the bridge subscribes again with the expected md5sum, so
  // roscpp refuses that publisher at connection and every right one connects.
  std::atomic<bool> strict{false};
  std::atomic<bool> resubscribe{false};
  std::mutex problem_mutex;
};

class BridgeRunner {
 public:
  // Creates every bridge's DDS side and checks every type against the message tree. Errors name
  // the bridge (its topics) and what is wrong; nothing is registered with ROS 1 yet.
  static Expected<std::unique_ptr<BridgeRunner>> create(const BridgeFile& file,
                                                        const ros1::Messages& messages,
                                                        dds::Participant& participant);
  ~BridgeRunner();

  // Registers every bridge with the ROS 1 master (subscribers and publishers). Call again after a
  // master restart: the old registrations are shut down first, so no bridge is there twice.
  void register_ros1(ros::NodeHandle& node);
  void shutdown_ros1();
  // Subscribes again, strictly, the bridges that heard a publisher of another definition. Main
  // thread, with the node register_ros1 got.
  void resubscribe_refused(ros::NodeHandle& node);

  // Forwards what DDS delivered (dds_to_ros1), waiting up to `timeout` for data. Main thread.
  void forward_dds(Duration timeout);

  [[nodiscard]] std::vector<std::unique_ptr<Bridge>>& bridges() { return bridges_; }
  [[nodiscard]] std::uint64_t registrations() const { return registrations_; }

 private:
  BridgeRunner() = default;
  void subscribe(Bridge& bridge, ros::NodeHandle& node);
  void on_ros1_message(Bridge& bridge, const ros::MessageEvent<topic_tools::ShapeShifter const>& event);

  std::vector<std::unique_ptr<Bridge>> bridges_;
  const ros1::Messages* messages_ = nullptr;
  std::mutex wake_mutex_;
  std::condition_variable wake_;
  std::atomic<bool> dds_data_{false};
  std::uint64_t registrations_ = 0;
};

// Monotonic nanoseconds (steady clock), for sample ages.
std::int64_t monotonic_ns();

}  // namespace hubrt::hubbridge
