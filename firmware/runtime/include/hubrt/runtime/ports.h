// Where a node's commands come from and where its State goes. The node-type layout wires these
// to DDS readers and writers; the hub layout to a distributor and a collector; tests to queues.
#pragma once

#include <optional>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"

namespace hubrt::runtime {

// One command as its source hands it over: the command, when its writer wrote it and, from a
// source that reads a clock, when it was taken.
template <class Command>
struct ReceivedCommand {
  // nullptr when none is pending. The pointee stays valid until the source's next call.
  const Command* command = nullptr;
  // The writer's wall clock when it wrote the command: the DDS sample's source timestamp
  // (dds_sample_info_t::source_timestamp; 0 when the writer sent none). A command's age is judged
  // from it (command_age.h). Absent for a command built in this process (tests, fuzz harnesses):
  // such a command is as old as its arrival.
  std::optional<WallTime> source_time;
  // The hub's wall clock read by the source just after the take (DdsCommandSource given a clock).
  // The cycle reads its clocks before it starts taking; a cycle thread held in between (a loaded
  // board preempting it for 100 ms) takes commands written after that reading, which against it
  // would look stamped in the future. Absent: the cycle's reading is the time of the take.
  std::optional<WallTime> take_wall;
};

// Thread-safety: called only from the cycle thread.
template <class Command>
class CommandSource {
 public:
  virtual ~CommandSource() = default;
  // The next received command (command == nullptr when none is pending), with its source
  // timestamp. Allocation-free. Errors: whatever the transport reports (the node logs them and
  // carries on).
  virtual Result<ReceivedCommand<Command>> next() noexcept = 0;
  // False only when the transport knows that no command has arrived since next() last returned
  // none (the DDS source: its reader's data-available listener sets a flag, next() clears it);
  // true when one may be waiting, or when the source cannot tell. A command step steps the nodes
  // whose source says true first (Hub::command_step), so that a command's echo does not wait for
  // the other nodes' work. A hint for the order only: every node still steps. Allocation-free.
  [[nodiscard]] virtual bool may_have_command() const noexcept { return true; }
};

// Thread-safety: called only from the cycle thread.
template <class State>
class StateSink {
 public:
  virtual ~StateSink() = default;
  // Publishes (or hands on) one State. Must not keep pointers into `state` after returning.
  virtual Status publish(const State& state) noexcept = 0;
  // True when a new reader of these States appeared since the last call (the transport saw it
  // match; the DDS sink's publication-matched listener): the node then publishes its State at
  // once, so that the reader need not wait for the next heartbeat. Consumes the event; allocation-
  // free. A sink nobody reads directly (the hub layout's collected node States) never has one.
  virtual bool take_new_reader() noexcept { return false; }
};

}  // namespace hubrt::runtime
