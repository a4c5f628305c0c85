// A ROS 2-style planner written on Fast DDS: it writes one Command type and reads one State type
// of a hub, with the types fastddsgen made from the .msg files of ros2/hub_msgs (nothing of hubrt's
// messages). `Types` names them: Command, State and their fastddsgen PubSubTypes
// (DockNodeTypes, DockEcuHubTypes in fastdds_dock_planner.h).
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/core/status/SubscriptionMatchedStatus.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/rtps/common/Time_t.h>
#include <fmt/format.h>

#include "hubrt/base/status.h"

#include "fastdds_loopback.h"

namespace hubrt::interop {

// A State as the planner received it: the sample and when it arrived (the test's clock).
template <class State>
struct Received {
  State state;
  std::chrono::steady_clock::time_point received;
};

// Thread-safety: send(), start_repeating() and stop_repeating() from one thread; the repeating
// sender runs on its own thread; the State functions from one thread.
template <class Types>
class FastDdsPlanner {
 public:
  using Command = typename Types::Command;
  using State = typename Types::State;
  using ReceivedState = Received<State>;

  // `command_topic`, `state_topic`: DDS names, i.e. ROS 2's "rt/<topic>".
  // `properties`: see LoopbackParticipant::create.
  static Expected<std::unique_ptr<FastDdsPlanner>> create(std::uint32_t domain_id, std::string command_topic,
                                                          std::string state_topic,
                                                          const ParticipantProperties& properties = {}) {
    std::unique_ptr<FastDdsPlanner> self(
        new FastDdsPlanner(std::move(command_topic), std::move(state_topic)));
    auto participant = LoopbackParticipant::create(domain_id, "fastdds-planner", properties);
    if (!participant) return std::move(participant).error();
    self->participant_ = std::move(*participant);
    auto writer = self->participant_->create_writer(
        self->command_topic_, eprosima::fastdds::dds::TypeSupport(new typename Types::CommandPubSubType()));
    if (!writer) return std::move(writer).error();
    self->writer_ = *writer;
    auto reader = self->participant_->create_reader(
        self->state_topic_, eprosima::fastdds::dds::TypeSupport(new typename Types::StatePubSubType()));
    if (!reader) return std::move(reader).error();
    self->reader_ = *reader;
    return self;
  }

  ~FastDdsPlanner() { (void)stop_repeating(); }
  FastDdsPlanner(const FastDdsPlanner&) = delete;
  FastDdsPlanner& operator=(const FastDdsPlanner&) = delete;

  // True once both the hub's command reader and its State writer matched ours (discovery in
  // both directions), within `timeout`.
  bool wait_for_hub(std::chrono::milliseconds timeout) const {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      if (matched_both()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

  // What discovery matched so far, for failure messages.
  std::string match_report() const {
    eprosima::fastdds::dds::PublicationMatchedStatus publication;
    eprosima::fastdds::dds::SubscriptionMatchedStatus subscription;
    (void)writer_->get_publication_matched_status(publication);
    (void)reader_->get_subscription_matched_status(subscription);
    return fmt::format("Fast DDS matched {} command reader(s) on {} and {} State writer(s) on {}",
                       publication.current_count, command_topic_, subscription.current_count, state_topic_);
  }

  // Writes one command. Errors: kIo when Fast DDS refuses the write.
  Expected<void> send(const Command& command) {
    Command copy = command;  // DataWriter::write takes a non-const pointer
    if (!writer_->write(&copy)) return make_error(ErrorCode::kIo, "Fast DDS refused to write a command");
    return {};
  }

  // Writes `command` every `period` on a thread of its own until stop_repeating() (a planner
  // repeats its wanted command: hubd's commands are state-based).
  void start_repeating(const Command& command, std::chrono::milliseconds period) {
    (void)stop_repeating();
    repeating_ = true;
    repeater_ = std::thread([this, command, period] {
      while (repeating_) {
        if (send(command)) {
          const std::lock_guard<std::mutex> lock(last_write_mutex_);
          last_write_ = std::chrono::steady_clock::now();
        }
        std::this_thread::sleep_for(period);
      }
    });
  }

  // Stops the repeating sender; returns when it last wrote.
  std::chrono::steady_clock::time_point stop_repeating() {
    repeating_ = false;
    if (repeater_.joinable()) repeater_.join();
    const std::lock_guard<std::mutex> lock(last_write_mutex_);
    return last_write_;
  }

  // The next State received, waiting up to `timeout`.
  std::optional<ReceivedState> next_state(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (true) {
      ReceivedState received;
      eprosima::fastdds::dds::SampleInfo info;
      if (reader_->take_next_sample(&received.state, &info) == ReturnCode_t::RETCODE_OK) {
        if (!info.valid_data) continue;  // a lifecycle notice (writer gone), not a State
        received.received = std::chrono::steady_clock::now();
        return received;
      }
      const auto left = deadline - std::chrono::steady_clock::now();
      if (left <= std::chrono::steady_clock::duration::zero()) return std::nullopt;
      const auto wait_ms = std::chrono::duration_cast<std::chrono::milliseconds>(left).count() + 1;
      (void)reader_->wait_for_unread_message(eprosima::fastrtps::Duration_t(
          static_cast<std::int32_t>(wait_ms / 1000), static_cast<std::uint32_t>(wait_ms % 1000) * 1000000U));
    }
  }

  // Takes States until one satisfies `predicate` (returned) or `timeout` passes.
  std::optional<ReceivedState> wait_for_state(const std::function<bool(const State&)>& predicate,
                                              std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      auto received = next_state(left);
      if (received && predicate(received->state)) return received;
    }
    return std::nullopt;
  }

  // Drops every State received so far.
  void drain() {
    while (next_state(std::chrono::milliseconds(0))) {
    }
  }

 private:
  FastDdsPlanner(std::string command_topic, std::string state_topic)
      : command_topic_(std::move(command_topic)), state_topic_(std::move(state_topic)) {}

  bool matched_both() const {
    eprosima::fastdds::dds::PublicationMatchedStatus publication;
    eprosima::fastdds::dds::SubscriptionMatchedStatus subscription;
    (void)writer_->get_publication_matched_status(publication);
    (void)reader_->get_subscription_matched_status(subscription);
    return publication.current_count > 0 && subscription.current_count > 0;
  }

  std::string command_topic_;
  std::string state_topic_;
  std::unique_ptr<LoopbackParticipant> participant_;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
  std::thread repeater_;
  std::atomic<bool> repeating_{false};
  std::mutex last_write_mutex_;
  std::chrono::steady_clock::time_point last_write_;
};

}  // namespace hubrt::interop
