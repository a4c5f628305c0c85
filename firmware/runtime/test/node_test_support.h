// In-memory ports for node tests: a queue of commands and a sink that counts what it publishes.
#pragma once

#include <deque>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "hubrt/runtime/ports.h"

#include "valve_logic.h"

namespace hubrt::runtime::testing {

// A command whose strings live as long as it does.
struct OwnedValveCommand {
  std::string target_type = "valve";
  std::string target_name = "v1";
  std::string action = "open";
  float pressure_bar = 2.5f;
  std::vector<std::string> tags;

  // The wire struct (its tags point into this object); valid until it is changed or destroyed.
  // Strings longer than the IDL bound (256) are cut, as no peer could send them.
  ValveCommand wire() {
    message_ = hubrt_test::ValveCommand();
    message_.set_target_type(target_type);
    message_.set_target_name(target_name);
    message_.set_action(action);
    message_.set_pressure_bar(pressure_bar);
    for (const auto& tag : tags) message_.tags().push_back(tag);
    return message_.wire();
  }

 private:
  hubrt_test::ValveCommand message_;
};

class QueueSource final : public CommandSource<ValveCommand> {
 public:
  // Copies the command and builds its wire form now, so that next() never allocates.
  void push(const OwnedValveCommand& command) { push(command, std::nullopt); }
  // With the source timestamp its writer would have given it (DDS: the writer's wall clock) and
  // the hub's wall clock at its take, as a source that reads a clock reports it.
  void push(const OwnedValveCommand& command, std::optional<WallTime> written,
            std::optional<WallTime> take_wall = std::nullopt) {
    auto owned = std::make_unique<OwnedValveCommand>(command);
    wires_.push_back(owned->wire());
    stamps_.push_back(written);
    take_walls_.push_back(take_wall);
    queue_.push_back(std::move(owned));
  }
  void fail_next() { fail_next_ = true; }
  // Limits delivery to the first `count` commands pushed so far (all, by default), so that a test
  // can queue everything up front and hand commands out per cycle without allocating.
  void deliver_up_to(std::size_t count) { limit_ = count; }
  Result<ReceivedCommand<ValveCommand>> next() noexcept override {
    if (fail_next_) {
      fail_next_ = false;
      return Status(ErrorCode::kIo);
    }
    if (queue_.empty() || delivered_ >= limit_) return ReceivedCommand<ValveCommand>{};
    ++delivered_;
    current_ = std::move(queue_.front());
    queue_.pop_front();
    wire_ = wires_.front();
    wires_.pop_front();
    const std::optional<WallTime> stamp = stamps_.front();
    stamps_.pop_front();
    const std::optional<WallTime> take_wall = take_walls_.front();
    take_walls_.pop_front();
    return ReceivedCommand<ValveCommand>{&wire_, stamp, take_wall};
  }
  [[nodiscard]] std::size_t pending() const { return queue_.size(); }

 private:
  std::deque<std::unique_ptr<OwnedValveCommand>> queue_;
  std::deque<ValveCommand> wires_;
  std::deque<std::optional<WallTime>> stamps_;
  std::deque<std::optional<WallTime>> take_walls_;
  std::unique_ptr<OwnedValveCommand> current_;
  ValveCommand wire_{};
  bool fail_next_ = false;
  std::size_t delivered_ = 0;
  std::size_t limit_ = SIZE_MAX;
};

class CountingSink final : public StateSink<ValveState> {
 public:
  Status publish(const ValveState& state) noexcept override {
    ++count;
    last_seq = state.header.seq;
    last_sec = state.header.stamp.sec;
    return Status::ok();
  }
  // A reader "matches" when a test sets new_reader; the node consumes it in its next step.
  bool take_new_reader() noexcept override { return std::exchange(new_reader, false); }
  bool new_reader = false;
  std::uint64_t count = 0;
  std::uint64_t last_seq = 0;
  std::int32_t last_sec = 0;
};

}  // namespace hubrt::runtime::testing
