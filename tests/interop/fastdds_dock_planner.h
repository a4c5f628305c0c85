// A ROS 2-style planner for a Dock ECU written on Fast DDS: it writes DockCommand on
// /dock/command and reads DockState from /dock_ecu/dock/state, with the types fastddsgen made
// from ros2/hub_msgs/msg/*.msg (nothing of hubrt's messages).
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "hubrt/base/status.h"

#include "fastdds_loopback.h"
#include "hub_msgs_plain.h"

namespace hubrt::interop {

// A State as the planner received it: the sample and when it arrived (the test's clock).
struct ReceivedState {
  hub_msgs::msg::DockState state;
  std::chrono::steady_clock::time_point received;
};

// Every text in the State's error_list, joined with "; " (for searching and failure messages).
std::string joined_errors(const hub_msgs::msg::DockState& state);

// A command as ROS 2 code writes it.
hub_msgs::msg::DockCommand dock_command(const std::string& target_type, const std::string& target_name,
                                        const std::string& action);

// Thread-safety: send(), start_repeating() and stop_repeating() from one thread; the repeating
// sender runs on its own thread; the State functions from one thread.
class FastDdsDockPlanner {
 public:
  // ROS 2's names on the wire: topic "rt/<topic>", types hub_msgs::msg::dds_::<Type>_.
  static constexpr const char* kCommandTopic = "rt/dock/command";
  static constexpr const char* kStateTopic = "rt/dock_ecu/dock/state";

  static Expected<std::unique_ptr<FastDdsDockPlanner>> create(std::uint32_t domain_id);
  ~FastDdsDockPlanner();
  FastDdsDockPlanner(const FastDdsDockPlanner&) = delete;
  FastDdsDockPlanner& operator=(const FastDdsDockPlanner&) = delete;

  // True once both the hub's command reader and its State writer matched ours (discovery in
  // both directions), within `timeout`.
  bool wait_for_hub(std::chrono::milliseconds timeout) const;
  // What discovery matched so far, for failure messages.
  std::string match_report() const;

  // Writes one command. Errors: kIo when Fast DDS refuses the write.
  Expected<void> send(const hub_msgs::msg::DockCommand& command);
  // Writes `command` every `period` on a thread of its own until stop_repeating() (a planner
  // repeats its wanted command: hubd's commands are state-based). Returns the time of the last
  // write when stopped.
  void start_repeating(const hub_msgs::msg::DockCommand& command, std::chrono::milliseconds period);
  std::chrono::steady_clock::time_point stop_repeating();

  // The next State received, waiting up to `timeout`.
  std::optional<ReceivedState> next_state(std::chrono::milliseconds timeout);
  // Takes States until one satisfies `predicate` (returned) or `timeout` passes.
  std::optional<ReceivedState> wait_for_state(
      const std::function<bool(const hub_msgs::msg::DockState&)>& predicate,
      std::chrono::milliseconds timeout);
  // Drops every State received so far.
  void drain();

 private:
  FastDdsDockPlanner() = default;

  std::unique_ptr<LoopbackParticipant> participant_;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
  std::thread repeater_;
  std::atomic<bool> repeating_{false};
  std::mutex last_write_mutex_;
  std::chrono::steady_clock::time_point last_write_;
};

}  // namespace hubrt::interop
