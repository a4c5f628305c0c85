// A node: one piece of equipment with a Command type and a State type (the paper's §5.3). The
// generic part here does what every node does — command intake and validation, echo, fresh_msg,
// t_plus, got_reset, error_list, the watchdog, the lifecycle (lifecycle.h), the State header — and
// calls the node type's Logic for what only it knows.
#pragma once

#include <algorithm>
#include <array>
#include <concepts>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>

#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "hubrt/base/time.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/runtime/arena.h"
#include "hubrt/runtime/command_age.h"
#include "hubrt/runtime/command_observer.h"
#include "hubrt/runtime/command_reports.h"
#include "hubrt/runtime/command_tracker.h"
#include "hubrt/runtime/error_list.h"
#include "hubrt/runtime/escaped_text.h"
#include "hubrt/runtime/hub_alerts.h"
#include "hubrt/runtime/immediate_state_budget.h"
#include "hubrt/runtime/lifecycle.h"
#include "hubrt/runtime/message_ops.h"
#include "hubrt/runtime/ports.h"

namespace hubrt::runtime {

inline constexpr std::string_view kResetAction = "reset";
// Longest string accepted in any command field, in bytes.
inline constexpr std::size_t kMaxCommandString = 64;

// What a node type implements. All calls happen on the cycle thread and must not allocate.
// Command is the generated read-only view of the node's command (e.g. hub_msgs::DockCommandView)
// and State the generated owning State type (e.g. hub_msgs::DockState); see firmware/msgs/README.md.
template <class L>
concept NodeLogic = requires(L& logic, const L& const_logic, const typename L::Command& command,
                             typename L::State& state, ErrorList& errors, Problem& problem, Time now) {
  typename L::Command;
  typename L::State;
  { L::kType } -> std::convertible_to<std::string_view>;
  { L::kActions.size() } -> std::convertible_to<std::size_t>;
  // Checks node-specific fields (ranges, names) of a command whose action is already known to be
  // one of kActions. Returns false and describes the problem to reject it.
  { const_logic.validate(command, problem) } -> std::same_as<bool>;
  // Samples the node's inputs.
  { logic.read_inputs(now) } -> std::same_as<void>;
  // What keeps the node from following its command, judged from what it knows after
  // read_inputs(): a latched fault that needs a reset (kFault), a device it needs that is not
  // open (kDevicesMissing), or nothing (kOk). Decides the node's lifecycle state (lifecycle.h).
  { const_logic.condition() } -> std::same_as<NodeCondition>;
  // Decides and writes the outputs for the command in force; nullptr means the node is not
  // operational (no command in force — never received, the watchdog tripped — or condition() was
  // not kOk): the node's safe state.
  { logic.update(static_cast<const typename L::Command*>(nullptr), now) } -> std::same_as<void>;
  // Clears latched faults (a reset command took effect).
  { logic.reset() } -> std::same_as<void>;
  // Fills the node-specific State fields and adds what is wrong right now.
  { logic.report(state, errors, now) } -> std::same_as<void>;
  // Drives the outputs to the safe state at once (the hub stopping).
  { logic.enter_safe_state() } -> std::same_as<void>;
};

enum class Addressing : std::uint8_t {
  kIgnoreOthers,  // node-type layout: the topic is shared; commands for other names are not ours
  kRejectOthers,  // hub layout: the distributor routed it here; another name is an error
};

struct NodeOptions {
  std::string name;
  Duration command_timeout = std::chrono::milliseconds(1000);
  Addressing addressing = Addressing::kIgnoreOthers;
  // Immediate States (outside the heartbeat): a token bucket refilled at one per this interval,
  // holding at most `immediate_state_burst` (ImmediateStateBudget).
  Duration immediate_state_interval = kDefaultImmediateStateInterval;
  std::uint32_t immediate_state_burst = kDefaultImmediateStateBurst;
  // How far the planner's and the hub's clocks agree (command_age.h); std::nullopt: not synced.
  ClockTolerance clock_tolerance = kDefaultClockTolerance;
  // Told of every command taken (may be null; must outlive the node).
  CommandObserver* command_observer = nullptr;
  std::shared_ptr<spdlog::logger> log;
};

enum class Health : std::uint8_t { kOk = 0, kWarn = 1, kError = 2, kStale = 3 };  // = DiagnosticStatus levels

// What the hub's cycle sees of a node.
class NodeBase {
 public:
  virtual ~NodeBase() = default;
  [[nodiscard]] virtual std::string_view name() const noexcept = 0;
  [[nodiscard]] virtual std::string_view type() const noexcept = 0;
  // Takes commands, runs the watchdog and the logic, writes outputs, rebuilds the State.
  // Returns true when a command took effect, i.e. the State should be published now.
  virtual bool step(const Instant& now) noexcept = 0;
  // The heartbeat: stamps and publishes the State built by the last step, always.
  virtual Status publish(const Instant& now) noexcept = 0;
  // After a step between heartbeats: stamps and publishes the State when a command took effect
  // in it (`took_effect`), a new reader of the State matched (StateSink::take_new_reader, taken
  // in the step like a command), or a change held back earlier still waits, and the node's
  // ImmediateStateBudget allows it now; otherwise holds the change back for the next State.
  // A State for a new reader counts in the budget like a command's (a peer creating readers in a
  // loop cannot make the hub publish more than a command flood could).
  virtual Status publish_if_due(const Instant& now, bool took_effect) noexcept = 0;
  // A command may be waiting for this node (CommandSource::may_have_command): a command step
  // steps it before the nodes without one. True when the node cannot tell.
  [[nodiscard]] virtual bool may_have_command() const noexcept { return true; }
  // The hub is stopping: drives the outputs safe; the node's lifecycle goes to safe.
  virtual void enter_safe_state() noexcept = 0;
  [[nodiscard]] virtual Health health() const noexcept = 0;
  // First entry of the error list, or empty.
  [[nodiscard]] virtual std::string_view first_error() const noexcept = 0;
  [[nodiscard]] virtual std::uint64_t published() const noexcept = 0;
  [[nodiscard]] virtual std::uint64_t rejected() const noexcept = 0;
  // Commands dropped as too old to act, or as queued during a stall (command_age.h).
  [[nodiscard]] virtual std::uint64_t commands_stale() const noexcept { return 0; }
  // The judge of the commands' ages, with the clock offsets it saw (command_age.h); null for a
  // node that takes no commands.
  [[nodiscard]] virtual const CommandAgeJudge* command_ages() const noexcept { return nullptr; }
  // The cycle could not run until `now`, `late` past its deadline (Hub::note_late). When that is
  // longer than the command timeout, what queued meanwhile is drained now and every command taken
  // before `discard_until` is discarded: only one that arrives after the hub caught up acts.
  virtual void note_late(const Instant& /*now*/, Duration /*late*/, Time /*discard_until*/) noexcept {}
  // Changes whose immediate State the budget held back (they went out with a later State).
  [[nodiscard]] virtual std::uint64_t states_deferred() const noexcept = 0;

  // The hub-wide alerts this node puts first in its error_list (nullptr: none). Set while wiring;
  // `alerts` must outlive the node.
  void watch_alerts(const HubAlerts* alerts) noexcept { alerts_ = alerts; }

  // The node's lifecycle state as of its last step, with the reason and number of transitions.
  [[nodiscard]] const LifecycleState& lifecycle() const noexcept { return lifecycle_; }

 protected:
  const HubAlerts* alerts_ = nullptr;
  // Created once the hub type has opened (or begun retrying) the node's devices.
  LifecycleState lifecycle_{Lifecycle::kOpeningDevices, "devices opened; no cycle run yet"};
};

template <NodeLogic Logic>
class Node final : public NodeBase {
 public:
  using Command = typename Logic::Command;
  using State = typename Logic::State;
  // The idlc C structs on the wire behind the typed classes.
  using CommandWire = msgs::typed::wire_t<Command>;
  using StateWire = msgs::typed::wire_t<State>;
  static_assert(!std::is_same_v<Command, CommandWire> && !std::is_same_v<State, StateWire>,
                "Logic::Command and Logic::State are the generated typed classes (<idl>_typed.h), "
                "e.g. hub_msgs::DockCommandView and hub_msgs::DockState");

  static constexpr std::size_t kEchoArenaBytes = 4096;

  // `ops` describes CommandWire; `source` and `sink` must outlive the node.
  Node(NodeOptions options, Logic logic, CommandSource<CommandWire>& source, StateSink<StateWire>& sink,
       const MessageOps& ops)
      : options_(std::move(options)),
        logic_(std::move(logic)),
        source_(source),
        sink_(sink),
        ops_(ops),
        tracker_(options_.command_timeout),
        ages_(options_.command_timeout, options_.clock_tolerance),
        budget_(options_.immediate_state_interval, options_.immediate_state_burst),
        arenas_{Arena(kEchoArenaBytes), Arena(kEchoArenaBytes)} {
    static_assert(
        std::find(Logic::kActions.begin(), Logic::kActions.end(), kResetAction) != Logic::kActions.end(),
        "every node type accepts the reset action");
    if (!options_.log) options_.log = spdlog::default_logger();
    reports_.emplace(options_.name, options_.command_timeout, options_.log.get());
    // The configuration checks node names (a ROS name token of at most kMaxCommandString bytes).
    state_.set_name(options_.name);
  }
  ~Node() override = default;
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  [[nodiscard]] std::string_view name() const noexcept override { return options_.name; }
  [[nodiscard]] std::string_view type() const noexcept override { return Logic::kType; }
  [[nodiscard]] Logic& logic() noexcept { return logic_; }
  [[nodiscard]] const State& state() const noexcept { return state_; }
  [[nodiscard]] const ErrorList& errors() const noexcept { return errors_; }
  [[nodiscard]] const CommandTracker& tracker() const noexcept { return tracker_; }
  // When the last valid command taken was written and taken (the hub layout hands its source
  // timestamp on with the node fragments).
  [[nodiscard]] const CommandTimes& last_valid_command() const noexcept { return last_valid_; }

  bool step(const Instant& now) noexcept override {
    const bool took_effect = advance(now);
    rebuild_state(now.mono);
    return took_effect;
  }

  // The two halves of step(), for layouts that must run something in between (the hub layout
  // distributes the hub command after its own intake and collects node States before its own).
  // advance(): takes commands, runs the watchdog, reads inputs, decides the lifecycle state,
  // runs the logic (given the command in force only while operational), writes outputs.
  bool advance(const Instant& now) noexcept {
    const bool took_effect = take_commands(now);
    new_reader_ |= sink_.take_new_reader();
    if (tracker_.check(now.mono) == CommandTracker::Watchdog::kTripped) {
      options_.log->warn("{}: no valid command for more than {:.3f} s: outputs to safe state", options_.name,
                         to_seconds(options_.command_timeout));
    }
    logic_.read_inputs(now.mono);
    transition_to_report_ |= decide_lifecycle();
    const bool operational = lifecycle_.state() == Lifecycle::kOperational;
    const Command in_force(echo());
    logic_.update(operational ? &in_force : nullptr, now.mono);
    return took_effect;
  }
  // Rebuilds the State (common fields and the logic's) from what advance() left.
  void rebuild_state(Time now) noexcept {
    errors_.clear();
    if (alerts_ != nullptr) {
      for (std::size_t i = 0; i < alerts_->size(); ++i) errors_.add("{}", alerts_->at(i));
    }
    // A rejection stays visible for one command timeout, or until a valid command takes effect;
    // a stale command for one command timeout.
    reports_->add_to(errors_, now);
    if (tracker_.has_echo() && !tracker_.fresh()) {
      errors_.add("command timeout: no valid command for {:.2f} s (limit {:.2f} s); outputs in safe state",
                  to_seconds(tracker_.since_last_command(now)), to_seconds(options_.command_timeout));
    }
    const std::size_t first_logic_error = errors_.size();
    logic_.report(state_, errors_, now);
    if (transition_to_report_) {
      transition_to_report_ = false;
      report_transition(first_logic_error);
    }
    state_.header().set_lifecycle(static_cast<std::uint8_t>(lifecycle_.state()));
    // A plain copy of the echo's C struct: whatever sequences a command type has point into
    // arenas_, which live as long as the node (and the State).
    state_.wire().echo = echo();
    state_.set_fresh_msg(tracker_.fresh());
    state_.set_t_plus(static_cast<float>(tracker_.t_plus(now)));
    state_.set_got_reset(tracker_.got_reset());
    errors_.copy_to(state_.error_list());
  }

  Status publish(const Instant& now) noexcept override {
    budget_.on_heartbeat();
    new_reader_ = false;  // the heartbeat reaches the new reader too
    return stamp_and_publish(now);
  }

  Status publish_if_due(const Instant& now, bool took_effect) noexcept override {
    const bool changed = took_effect || new_reader_;
    new_reader_ = false;  // a State the budget holds back goes out with the next one
    if (!budget_.publish_now(now.mono, changed)) return Status::ok();
    return stamp_and_publish(now);
  }

  // Stamps the State built by the last step and hands it to the sink.
  Status stamp_and_publish(const Instant& now) noexcept {
    state_.header().set_seq(++published_);
    state_.header().stamp().set_sec(static_cast<std::int32_t>(now.wall.ns_since_epoch / 1'000'000'000));
    state_.header().stamp().set_nanosec(static_cast<std::uint32_t>(now.wall.ns_since_epoch % 1'000'000'000));
    return sink_.publish(state_.wire());
  }

  [[nodiscard]] bool may_have_command() const noexcept override { return source_.may_have_command(); }

  void enter_safe_state() noexcept override {
    stopping_ = true;
    if (lifecycle_.enter(Lifecycle::kSafe, "hub stopping: outputs driven safe"))
      report_transition(errors_.size());
    state_.header().set_lifecycle(static_cast<std::uint8_t>(lifecycle_.state()));
    logic_.enter_safe_state();
  }

  [[nodiscard]] Health health() const noexcept override {
    if (!errors_.empty()) return tracker_.has_echo() && !tracker_.fresh() ? Health::kStale : Health::kError;
    return tracker_.fresh() ? Health::kOk : Health::kWarn;
  }
  [[nodiscard]] std::string_view first_error() const noexcept override {
    return errors_.empty() ? std::string_view() : errors_.at(0);
  }
  [[nodiscard]] std::uint64_t published() const noexcept override { return published_; }
  [[nodiscard]] std::uint64_t rejected() const noexcept override { return reports_->rejected_count(); }
  [[nodiscard]] std::uint64_t commands_stale() const noexcept override { return reports_->stale_count(); }
  [[nodiscard]] const CommandAgeJudge* command_ages() const noexcept override { return &ages_; }

  void note_late(const Instant& now, Duration late, Time discard_until) noexcept override {
    if (late <= options_.command_timeout) return;
    ages_.begin_discarding(discard_until);
    const std::uint64_t before = reports_->stale_count();
    take_commands(now);  // drains what queued meanwhile: each is judged kQueued
    options_.log->warn(
        "{}: the hub could not run for {:.3f} s (more than the command timeout): {} queued "
        "command(s) discarded; commands act again once it has caught up",
        options_.name, to_seconds(late), reports_->stale_count() - before);
  }
  [[nodiscard]] std::uint64_t states_deferred() const noexcept override { return budget_.deferred(); }

 private:
  // Applies the lifecycle rule (lifecycle.h) for this step; returns true on a transition.
  bool decide_lifecycle() noexcept {
    const Lifecycle next = node_lifecycle(stopping_, tracker_.in_force(), logic_.condition());
    switch (next) {
      case Lifecycle::kOperational:
        return lifecycle_.enter(next, "command '{}' in force", Escaped{Command(echo()).action()});
      case Lifecycle::kFault:
        return lifecycle_.enter(next, "latched fault, send reset to clear");
      case Lifecycle::kRecovering:
        return lifecycle_.enter(next, "a device the node needs is not open, retrying");
      default:
        if (stopping_) return lifecycle_.enter(next, "hub stopping: outputs driven safe");
        if (!tracker_.has_echo()) return lifecycle_.enter(next, "no command received yet");
        return lifecycle_.enter(next, "command timeout: no valid command for more than {:.3f} s",
                                to_seconds(options_.command_timeout));
    }
  }

  // Completes the reason of the transition just made with the logic's first error (a fault or a
  // missing device names itself there), then logs it: once per transition.
  void report_transition(std::size_t first_logic_error) noexcept {
    const Lifecycle state = lifecycle_.state();
    if ((state == Lifecycle::kFault || state == Lifecycle::kRecovering) &&
        errors_.size() > first_logic_error) {
      lifecycle_.add_detail(errors_.at(first_logic_error));
    }
    const auto level = state == Lifecycle::kOperational || state == Lifecycle::kSafe ? spdlog::level::info
                                                                                     : spdlog::level::warn;
    options_.log->log(level, "{}: lifecycle {} -> {} (transition {}): {}", options_.name,
                      lifecycle_name(lifecycle_.previous()), lifecycle_.name(), lifecycle_.transitions(),
                      lifecycle_.reason());
  }

  // Drains the source; the last valid young command wins. Returns true when one took effect.
  bool take_commands(const Instant& now) noexcept {
    bool took_effect = false;
    for (;;) {
      const Result<ReceivedCommand<CommandWire>> next = source_.next();
      if (!next.is_ok()) {
        options_.log->error("{}: taking commands failed: {}", options_.name, to_string(next.status().code()));
        break;
      }
      const CommandWire* wire = next.value().command;
      if (wire == nullptr) break;
      const Command command(*wire);
      const CommandTimes times{next.value().source_time, now, next.value().take_wall};
      const CommandOutcome outcome = intake(command, times);
      if (options_.command_observer != nullptr)
        options_.command_observer->on_command(options_.name, wire, times, outcome);
      took_effect |= outcome == CommandOutcome::kTookEffect;
    }
    return took_effect;
  }

  // One command taken from the source: addressed here? young enough? valid? Then recorded.
  CommandOutcome intake(const Command& command, const CommandTimes& times) noexcept {
    if (!addressed_here(command)) return CommandOutcome::kNotAddressed;
    const Time now = times.taken.mono;
    const JudgedAge age = ages_.judge(times);
    switch (age.verdict) {
      case AgeVerdict::kStale:
      case AgeVerdict::kQueued:
        reports_->stale(now, age);
        return age.verdict == AgeVerdict::kStale ? CommandOutcome::kStale : CommandOutcome::kQueued;
      case AgeVerdict::kFuture:
        reports_->problem().format(
            "stamped {:.3f} s in the future, beyond the clock tolerance ({:.0f} ms): the planner's and "
            "the hub's clocks disagree",
            -to_seconds(age.offset), to_seconds(ages_.tolerance().value_or(Duration::zero())) * 1e3);
        reports_->rejected(now);
        return CommandOutcome::kRejected;
      case AgeVerdict::kUnstamped:
        reports_->problem().assign("no source timestamp: its age cannot be judged (clock_tolerance_ms)");
        reports_->rejected(now);
        return CommandOutcome::kRejected;
      case AgeVerdict::kYoung:
        break;
    }
    if (!accept(command, now)) return CommandOutcome::kRejected;
    const CommandOutcome outcome = take(command, now, age.written);
    if (outcome != CommandOutcome::kRejected) last_valid_ = times;
    return outcome;
  }

  [[nodiscard]] bool addressed_here(const Command& command) const noexcept {
    return options_.addressing == Addressing::kRejectOthers || command.target_name() == options_.name;
  }

  // Validates a command addressed here; a rejected one is reported and changes nothing else.
  // Command text quoted in a problem is Escaped: check_fields() already refused bad UTF-8, but
  // nothing a peer sends may reach a State unescaped.
  bool accept(const Command& command, Time now) noexcept {
    Problem& problem = reports_->problem();
    // Cyclone already dropped samples over the IDL bounds; this checks what the bounds cannot
    // (UTF-8, control characters, NaN) and the length of commands built in-process.
    bool ok = ops_.check_fields(&command.wire(), kMaxCommandString, problem);
    if (ok && command.target_name() != options_.name) {
      problem.format("wrong target: addressed to '{}', this node is '{}'", Escaped{command.target_name()},
                     options_.name);
      ok = false;
    }
    if (ok && command.target_type() != Logic::kType) {
      problem.format("wrong target type '{}' for node '{}' of type '{}'", Escaped{command.target_type()},
                     options_.name, Logic::kType);
      ok = false;
    }
    if (ok && !known_action(command.action())) {
      problem.format("unknown action '{}' (expected one of: {})", Escaped{command.action()},
                     fmt::join(Logic::kActions, ", "));
      ok = false;
    }
    if (ok && !logic_.validate(command, problem)) ok = false;
    if (ok) return true;
    reports_->rejected(now);
    return false;
  }

  // Records a valid command written at `written`; copies it into the echo when its content is new.
  CommandOutcome take(const Command& command, Time now, Time written) noexcept {
    const bool differs = !tracker_.has_echo() || !ops_.equal(&command.wire(), &echo());
    // Copy into the spare buffer first, so a command too large to hold leaves the echo intact.
    if (differs && !ops_.copy_into(&command.wire(), &echoes_[1 - current_], arenas_[1 - current_])) {
      reports_->problem().format("command too large to hold (more than {} bytes of strings and sequences)",
                                 kEchoArenaBytes);
      reports_->rejected(now);
      return CommandOutcome::kRejected;
    }
    if (differs) current_ = 1 - current_;
    const bool is_reset = command.action() == kResetAction;
    if (tracker_.on_valid_command(now, written, differs, is_reset) != CommandTracker::Arrival::kTookEffect)
      return CommandOutcome::kRepeat;
    reports_->clear_rejection();
    if (is_reset) logic_.reset();
    options_.log->debug("{}: command took effect: action '{}'", options_.name, Command(echo()).action());
    return CommandOutcome::kTookEffect;
  }

  [[nodiscard]] const CommandWire& echo() const noexcept { return echoes_[current_]; }

  [[nodiscard]] static bool known_action(std::string_view action) noexcept {
    return std::find(Logic::kActions.begin(), Logic::kActions.end(), action) != Logic::kActions.end();
  }

  NodeOptions options_;
  Logic logic_;
  CommandSource<CommandWire>& source_;
  StateSink<StateWire>& sink_;
  const MessageOps& ops_;
  CommandTracker tracker_;
  CommandAgeJudge ages_;
  ImmediateStateBudget budget_;
  // Double-buffered deep copies of the echoed command; echoes_[current_] is the echo.
  std::array<Arena, 2> arenas_;
  std::array<CommandWire, 2> echoes_{};
  int current_ = 0;
  State state_;  // owns the storage its sequences point into
  ErrorList errors_;
  std::optional<CommandReports> reports_;  // made once options_.log is set
  CommandTimes last_valid_{};
  bool stopping_ = false;              // enter_safe_state() was called: safe for good
  bool transition_to_report_ = false;  // advance() changed the lifecycle; rebuild_state() logs it
  bool new_reader_ = false;            // a reader of the State matched since it was last published
  std::uint64_t published_ = 0;
};

}  // namespace hubrt::runtime
