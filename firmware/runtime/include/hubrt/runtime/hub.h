// A hub: its nodes and the fixed-rate cycle over them. Each cycle: every node takes its
// commands, reads inputs, runs its logic, writes outputs, rebuilds its State — then every State
// is published (the heartbeat). A command that arrives between cycles triggers the same step at
// once and publishes only the States whose command took effect, within each node's budget of
// immediate States (ImmediateStateBudget; a change held back goes out with the next State).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <spdlog/logger.h>

#include "hubrt/base/time.h"
#include "hubrt/runtime/hub_alerts.h"
#include "hubrt/runtime/lifecycle.h"
#include "hubrt/runtime/node.h"
#include "hubrt/runtime/stage_trace.h"

namespace hubrt::runtime {

// Something a layout adds around the nodes (the hub layout's distributor and collector).
// Called on the cycle thread, allocation-free.
class CycleStage {
 public:
  virtual ~CycleStage() = default;
  // Before the nodes step: e.g. split a hub command into node commands.
  virtual void before_nodes(const Instant& now) noexcept = 0;
  // After the nodes stepped. `publish_all`: this is a periodic cycle; `took_effect`: some node's
  // command took effect. E.g. assemble and publish the hub State.
  virtual void after_nodes(const Instant& now, bool publish_all, bool took_effect) noexcept = 0;
  // Once, after the nodes entered their safe state on the way out: e.g. the simulation bridge
  // publishes the outputs a last time, so that watchers see them safe.
  virtual void after_safe_state(const Instant& /*now*/) noexcept {}
  // The cycle could not run until `now`, `late` past its deadline (Hub::note_late): a stage that
  // takes commands itself (the hub layout's hub-level command) drops what queued meanwhile.
  virtual void note_late(const Instant& /*now*/, Duration /*late*/, Time /*discard_until*/) noexcept {}

  // Immediate States this stage held back for its budget (the hub layout's hub State).
  [[nodiscard]] virtual std::uint64_t states_deferred() const noexcept { return 0; }
  // The node that takes the hub-level command, when the stage has one (the hub layout): its
  // rejections, stale commands and clock offsets go into /diagnostics with the hub's.
  [[nodiscard]] virtual const NodeBase* hub_level_node() const noexcept { return nullptr; }
};

struct CycleStats {
  std::uint64_t cycles = 0;         // periodic cycles run
  std::uint64_t command_steps = 0;  // steps triggered by arriving commands
  std::uint64_t overruns = 0;       // periods missed because a cycle ran late
  std::uint64_t publish_errors = 0;
  Duration longest_late{0};  // the longest the cycle was held past a deadline (note_late)
  Duration last_cycle{0};    // execution time of the last periodic cycle
  Duration max_cycle{0};
};

struct HubOptions {
  std::string type;  // hub type, e.g. "dock_ecu"
  std::string name;  // instance name, unique on the domain
  Duration period = std::chrono::milliseconds(100);
  std::shared_ptr<spdlog::logger> log;
};

// Thread-safety: everything runs on the cycle thread.
class Hub {
 public:
  explicit Hub(HubOptions options);
  Hub(const Hub&) = delete;
  Hub& operator=(const Hub&) = delete;

  // Wiring; before the first cycle only. `owned` keeps alive what nodes reference (ports).
  // Every node added reports alerts() first in its error_list.
  void add_node(std::unique_ptr<NodeBase> node);
  void add_stage(std::unique_ptr<CycleStage> stage);
  // A stage that must run before every other (reading inputs the others use).
  void add_first_stage(std::unique_ptr<CycleStage> stage);
  void keep_alive(std::shared_ptr<void> owned);

  // Stamps, in command steps, when the first node whose command took effect stepped and when its
  // State was written (stage_trace.h; null: none). The node's own State, as the node-type layout
  // publishes it; in the hub layout the hub State goes out after every node stepped, later than
  // the "written" stamp. CycleRunner::run() sets it.
  void trace_stages(StageTrace* trace) noexcept { trace_ = trace; }

  // A periodic cycle at `now`; publishes every State.
  void cycle(const Instant& now) noexcept;
  // A step between cycles because commands arrived; publishes States whose command took effect.
  // The nodes a command may be waiting for (NodeBase::may_have_command) step first, in the order
  // they were added, then the others: a command's echo is not held behind other nodes' work.
  void command_step(const Instant& now) noexcept;
  // Overruns observed by the timer (periods that passed without a cycle).
  void count_overruns(std::uint64_t missed) noexcept { stats_.overruns += missed; }
  // The cycle could not run until `now`, `late` past its deadline (CycleRunner calls this when
  // that is more than a period: the process was stopped or paused, or a step blocked). Before any
  // step takes a command: every node (and stage) whose command timeout `late` exceeds drains what
  // queued meanwhile and discards every command it takes until the hub has caught up, i.e. for
  // max(kStallSettle, one period) from `now` (command_age.h).
  void note_late(const Instant& now, Duration late) noexcept;
  // Lifecycle phase: the hub type is about to open its nodes' devices (before the first
  // add_node()). The first cycle ends the phase: from then on the hub's state is its nodes' worst.
  void begin_opening_devices() noexcept;
  // Drives every node's outputs to its safe state (shutdown); the hub's lifecycle goes to stopping.
  void enter_safe_state() noexcept;
  // After enter_safe_state(), on the way out: lets every stage report the safe state at `now`.
  void report_safe_state(const Instant& now) noexcept;

  [[nodiscard]] const HubOptions& options() const noexcept { return options_; }
  [[nodiscard]] const CycleStats& stats() const noexcept { return stats_; }
  // The hub's overall lifecycle state (lifecycle.h), with the reason of its last transition.
  [[nodiscard]] const LifecycleState& lifecycle() const noexcept { return lifecycle_; }
  [[nodiscard]] const std::vector<std::unique_ptr<NodeBase>>& nodes() const noexcept { return nodes_; }
  [[nodiscard]] NodeBase* find_node(std::string_view name) const noexcept;
  // Immediate States held back by every node's and stage's budget, since start.
  [[nodiscard]] std::uint64_t states_deferred() const noexcept;
  // The hub layout's hub-level command node (CycleStage::hub_level_node), or null.
  [[nodiscard]] const NodeBase* hub_level_node() const noexcept;

  // Hub-wide conditions every node reports (set by a stage before the nodes step).
  [[nodiscard]] HubAlerts& alerts() noexcept { return alerts_; }
  [[nodiscard]] const HubAlerts& alerts() const noexcept { return alerts_; }

 private:
  void step(const Instant& now, bool publish_all) noexcept;
  // Steps node `index` (and publishes as the kind of step says); true when a command took effect.
  bool step_node(std::size_t index, const Instant& now, bool publish_all) noexcept;
  // The worst state of the nodes after a step, unless the hub is stopping.
  void derive_lifecycle() noexcept;
  void log_transition() const noexcept;

  HubOptions options_;
  std::vector<std::unique_ptr<NodeBase>> nodes_;
  std::vector<std::uint8_t> stepped_;  // per node, within one command step (sized by add_node)
  std::vector<std::unique_ptr<CycleStage>> stages_;
  std::vector<std::shared_ptr<void>> owned_;
  StageTrace* trace_ = nullptr;
  HubAlerts alerts_;
  CycleStats stats_;
  LifecycleState lifecycle_{Lifecycle::kConfiguring, "reading the hub and board files"};
};

}  // namespace hubrt::runtime
