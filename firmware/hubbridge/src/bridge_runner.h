// One hubbridge process: its bridges' DDS readers and writers, their ROS 1 subscribers and
// publishers (roscpp, topic_tools::ShapeShifter so that no type is compiled in). What keeps them
// registered across rosmaster restarts is MasterSync (master_sync.h).
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
#include "master_sync.h"

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
  HeardPublishers heard;                     // ros1_to_dds: who sends messages of the type
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

  // Subscribes and advertises every bridge through roscpp, which registers them with the master.
  // Once: after a master restart MasterSync registers them again without dropping their links.
  void register_ros1(ros::NodeHandle& node);
  void shutdown_ros1();
  // Subscribes again, strictly, the bridges that heard a publisher of another definition. Main
  // thread, with the node register_ros1 got.
  void resubscribe_refused(ros::NodeHandle& node);

  // Forwards what DDS delivered (dds_to_ros1), waiting up to `timeout` for data. Main thread.
  void forward_dds(Duration timeout);

  [[nodiscard]] std::vector<std::unique_ptr<Bridge>>& bridges() { return bridges_; }
  // Each bridge's ROS 1 side, in bridge order, for MasterSync.
  [[nodiscard]] std::vector<SyncedEndpoint> endpoints() const;
  // Per bridge (in order), the publishers heard at `since_ns` or later (none for dds_to_ros1).
  [[nodiscard]] std::vector<std::vector<std::string>> heard_since(std::int64_t since_ns) const;

 private:
  BridgeRunner() = default;
  void subscribe(Bridge& bridge, ros::NodeHandle& node);
  void on_ros1_message(Bridge& bridge, const ros::MessageEvent<topic_tools::ShapeShifter const>& event);

  std::vector<std::unique_ptr<Bridge>> bridges_;
  const ros1::Messages* messages_ = nullptr;
  std::mutex wake_mutex_;
  std::condition_variable wake_;
  std::atomic<bool> dds_data_{false};
};

// Monotonic nanoseconds (steady clock), for sample ages.
std::int64_t monotonic_ns();

}  // namespace hubrt::hubbridge
