#include "fastdds_dock_planner.h"

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/core/status/SubscriptionMatchedStatus.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fmt/format.h>

#include "hub_msgs_plainPubSubTypes.h"

namespace hubrt::interop {

namespace fdds = eprosima::fastdds::dds;
using std::chrono::milliseconds;
using std::chrono::steady_clock;

std::string joined_errors(const hub_msgs::msg::DockState& state) {
  std::string out;
  for (const auto& error : state.error_list()) out += error.to_string() + "; ";
  return out;
}

hub_msgs::msg::DockCommand dock_command(const std::string& target_type, const std::string& target_name,
                                        const std::string& action) {
  hub_msgs::msg::DockCommand command;
  command.target_type(target_type);
  command.target_name(target_name);
  command.action(action);
  return command;
}

Expected<std::unique_ptr<FastDdsDockPlanner>> FastDdsDockPlanner::create(std::uint32_t domain_id) {
  std::unique_ptr<FastDdsDockPlanner> self(new FastDdsDockPlanner());
  auto participant = LoopbackParticipant::create(domain_id, "fastdds-planner");
  if (!participant) return std::move(participant).error();
  self->participant_ = std::move(*participant);
  auto writer = self->participant_->create_writer(
      kCommandTopic, fdds::TypeSupport(new hub_msgs::msg::DockCommandPubSubType()));
  if (!writer) return std::move(writer).error();
  self->writer_ = *writer;
  auto reader = self->participant_->create_reader(
      kStateTopic, fdds::TypeSupport(new hub_msgs::msg::DockStatePubSubType()));
  if (!reader) return std::move(reader).error();
  self->reader_ = *reader;
  return self;
}

FastDdsDockPlanner::~FastDdsDockPlanner() {
  (void)stop_repeating();
}

bool FastDdsDockPlanner::wait_for_hub(milliseconds timeout) const {
  const auto deadline = steady_clock::now() + timeout;
  while (steady_clock::now() < deadline) {
    fdds::PublicationMatchedStatus publication;
    fdds::SubscriptionMatchedStatus subscription;
    (void)writer_->get_publication_matched_status(publication);
    (void)reader_->get_subscription_matched_status(subscription);
    if (publication.current_count > 0 && subscription.current_count > 0) return true;
    std::this_thread::sleep_for(milliseconds(20));
  }
  return false;
}

std::string FastDdsDockPlanner::match_report() const {
  fdds::PublicationMatchedStatus publication;
  fdds::SubscriptionMatchedStatus subscription;
  (void)writer_->get_publication_matched_status(publication);
  (void)reader_->get_subscription_matched_status(subscription);
  return fmt::format("Fast DDS matched {} command reader(s) on {} and {} State writer(s) on {}",
                     publication.current_count, kCommandTopic, subscription.current_count, kStateTopic);
}

Expected<void> FastDdsDockPlanner::send(const hub_msgs::msg::DockCommand& command) {
  hub_msgs::msg::DockCommand copy = command;  // DataWriter::write takes a non-const pointer
  if (!writer_->write(&copy)) return make_error(ErrorCode::kIo, "Fast DDS refused to write the command");
  return {};
}

void FastDdsDockPlanner::start_repeating(const hub_msgs::msg::DockCommand& command, milliseconds period) {
  (void)stop_repeating();
  repeating_ = true;
  repeater_ = std::thread([this, command, period] {
    while (repeating_) {
      if (send(command)) {
        const std::lock_guard<std::mutex> lock(last_write_mutex_);
        last_write_ = steady_clock::now();
      }
      std::this_thread::sleep_for(period);
    }
  });
}

steady_clock::time_point FastDdsDockPlanner::stop_repeating() {
  repeating_ = false;
  if (repeater_.joinable()) repeater_.join();
  const std::lock_guard<std::mutex> lock(last_write_mutex_);
  return last_write_;
}

std::optional<ReceivedState> FastDdsDockPlanner::next_state(milliseconds timeout) {
  const auto deadline = steady_clock::now() + timeout;
  while (true) {
    ReceivedState received;
    fdds::SampleInfo info;
    if (reader_->take_next_sample(&received.state, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;  // a lifecycle notice (writer gone), not a State
      received.received = steady_clock::now();
      return received;
    }
    const auto left = deadline - steady_clock::now();
    if (left <= steady_clock::duration::zero()) return std::nullopt;
    const auto wait = std::chrono::duration_cast<milliseconds>(left).count() + 1;
    (void)reader_->wait_for_unread_message(eprosima::fastrtps::Duration_t(
        static_cast<std::int32_t>(wait / 1000), static_cast<std::uint32_t>(wait % 1000) * 1000000U));
  }
}

std::optional<ReceivedState> FastDdsDockPlanner::wait_for_state(
    const std::function<bool(const hub_msgs::msg::DockState&)>& predicate, milliseconds timeout) {
  const auto deadline = steady_clock::now() + timeout;
  while (steady_clock::now() < deadline) {
    auto left = std::chrono::duration_cast<milliseconds>(deadline - steady_clock::now());
    auto received = next_state(left);
    if (received && predicate(received->state)) return received;
  }
  return std::nullopt;
}

void FastDdsDockPlanner::drain() {
  while (next_state(milliseconds(0))) {
  }
}

}  // namespace hubrt::interop
