// The node-type layout's ports: a node's commands come from a DDS reader, its State goes to a
// DDS writer. Both reuse one sample for their whole life, so the cycle allocates nothing here
// (Cyclone grows a taken sample's strings only when a longer one arrives).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <utility>

#include "hubrt/base/time.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/writer.h"
#include "hubrt/runtime/ports.h"

namespace hubrt::hub_api {

// History depth of a node's or hub's command reader. One: the node takes every command as soon
// as it arrives (the reader wakes the cycle thread for a command step) and the last command wins
// anyway, and with one sample per instance Cyclone reuses the instance's own sample slot for
// every arrival, where a deeper history mallocs a slot for each command that arrives while one is
// still unread (Cyclone 0.10.2 dds_rhc_default.c: alloc_sample, and add_sample replaces the
// oldest once the history is full). What a burst changes: of two commands arriving between two
// steps only the later is seen (and judged).
inline constexpr std::int32_t kCommandHistoryDepth = 1;

// Thread-safety: next() on the cycle thread only.
// `clock`: read right after each take that returns a command (ReceivedCommand::take_wall); must
// outlive the source. `arrived`: set (release) by the reader's data-available listener on
// Cyclone's thread when a command arrives; may be null (then may_have_command() always says true).
template <dds::TopicType Command>
class DdsCommandSource final : public runtime::CommandSource<Command> {
 public:
  DdsCommandSource(dds::Reader<Command> reader, const Clock& clock,
                   std::shared_ptr<std::atomic<bool>> arrived = nullptr)
      : reader_(std::move(reader)), clock_(&clock), arrived_(std::move(arrived)) {}

  // Each command comes with its DDS source timestamp (the writer's clock: SampleInfo::source_time)
  // and the hub's wall clock at the take, what its age is judged against (command_age.h).
  Result<runtime::ReceivedCommand<Command>> next() noexcept override {
    // Nothing arrived since the last take found the reader empty: no take (Cyclone's dds_take
    // locks the reader and its history cache to find nothing, ~650 instructions every periodic
    // cycle). The listener runs after the sample is in the reader (Cyclone 0.10.2
    // dds_rhc_default.c, dds_rhc_default_store: dds_reader_data_available_cb once the history
    // cache is unlocked), so a command seen by no flag yet is taken in the command step its
    // listener's wake starts.
    if (!may_have_command()) return runtime::ReceivedCommand<Command>{};
    // Cleared before the take: a command arriving during or after it sets the flag again.
    if (arrived_) arrived_->store(false, std::memory_order_relaxed);
    dds::SampleInfo info;
    const Result<bool> taken = reader_.take_next(sample_, &info);
    if (!taken.is_ok() || taken.value()) {
      if (arrived_) arrived_->store(true, std::memory_order_relaxed);  // more may follow
    }
    if (!taken.is_ok()) return taken.status();
    if (!taken.value()) return runtime::ReceivedCommand<Command>{};
    return runtime::ReceivedCommand<Command>{&sample_.get(), info.source_time, clock_->now().wall};
  }
  [[nodiscard]] bool may_have_command() const noexcept override {
    return !arrived_ || arrived_->load(std::memory_order_acquire);
  }
  [[nodiscard]] const dds::Reader<Command>& reader() const noexcept { return reader_; }

 private:
  dds::Reader<Command> reader_;
  const Clock* clock_;
  dds::Sample<Command> sample_;
  std::shared_ptr<std::atomic<bool>> arrived_;
};

// Thread-safety: publish() on the cycle thread only.
template <dds::TopicType State>
class DdsStateSink final : public runtime::StateSink<State> {
 public:
  explicit DdsStateSink(dds::Writer<State> writer) : writer_(std::move(writer)) {}
  Status publish(const State& state) noexcept override { return writer_.write(state); }
  bool take_new_reader() noexcept override { return writer_.take_new_readers() > 0; }
  [[nodiscard]] const dds::Writer<State>& writer() const noexcept { return writer_; }

 private:
  dds::Writer<State> writer_;
};

}  // namespace hubrt::hub_api
