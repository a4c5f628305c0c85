#include "hubrt/runtime/hub.h"

#include <algorithm>
#include <ctime>

#include <spdlog/spdlog.h>

namespace hubrt::runtime {
namespace {

// Wall time, not CPU time: a cycle that waits on a device is late even when it burns no CPU.
Duration monotonic_now() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::chrono::seconds(ts.tv_sec) + std::chrono::nanoseconds(ts.tv_nsec);
}

}  // namespace

Hub::Hub(HubOptions options) : options_(std::move(options)) {
  if (!options_.log) options_.log = spdlog::default_logger();
}

void Hub::add_node(std::unique_ptr<NodeBase> node) {
  node->watch_alerts(&alerts_);
  nodes_.push_back(std::move(node));
  stepped_.push_back(0);
}
void Hub::add_stage(std::unique_ptr<CycleStage> stage) {
  stages_.push_back(std::move(stage));
}

void Hub::add_first_stage(std::unique_ptr<CycleStage> stage) {
  // push_back + rotate rather than insert(begin()): GCC 12 at -O2 reports a false "potential null
  // pointer dereference" inside vector::insert, which -Werror turns into a broken release build.
  stages_.push_back(std::move(stage));
  std::rotate(stages_.begin(), stages_.end() - 1, stages_.end());
}
void Hub::keep_alive(std::shared_ptr<void> owned) {
  owned_.push_back(std::move(owned));
}

NodeBase* Hub::find_node(std::string_view name) const noexcept {
  for (const auto& node : nodes_) {
    if (node->name() == name) return node.get();
  }
  return nullptr;
}

void Hub::cycle(const Instant& now) noexcept {
  const Duration started = monotonic_now();
  ++stats_.cycles;
  step(now, true);
  stats_.last_cycle = monotonic_now() - started;
  if (stats_.last_cycle > stats_.max_cycle) stats_.max_cycle = stats_.last_cycle;
}

void Hub::command_step(const Instant& now) noexcept {
  ++stats_.command_steps;
  step(now, false);
}

void Hub::step(const Instant& now, bool publish_all) noexcept {
  for (const auto& stage : stages_) stage->before_nodes(now);
  bool any_took_effect = false;
  if (publish_all) {
    for (std::size_t i = 0; i < nodes_.size(); ++i) any_took_effect |= step_node(i, now, true);
  } else {
    // The nodes a command may be waiting for first, so that the echo goes out before the other
    // nodes read their inputs and rebuild their States; then every node not stepped yet. Whether
    // a command arrives in between changes the order only: each node steps exactly once.
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      stepped_[i] = nodes_[i]->may_have_command() ? 1 : 0;
      if (stepped_[i] != 0) any_took_effect |= step_node(i, now, false);
    }
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      if (stepped_[i] == 0) any_took_effect |= step_node(i, now, false);
    }
  }
  derive_lifecycle();
  for (const auto& stage : stages_) stage->after_nodes(now, publish_all, any_took_effect);
}

bool Hub::step_node(std::size_t index, const Instant& now, bool publish_all) noexcept {
  NodeBase& node = *nodes_[index];
  const bool took_effect = node.step(now);
  const bool traced = trace_ != nullptr && !publish_all && took_effect;
  if (traced) trace_->node_stepped();
  const Status published = publish_all ? node.publish(now) : node.publish_if_due(now, took_effect);
  if (traced) trace_->state_written();
  if (!published.is_ok()) ++stats_.publish_errors;
  return took_effect;
}

void Hub::note_late(const Instant& now, Duration late) noexcept {
  if (late > stats_.longest_late) stats_.longest_late = late;
  const Time discard_until = now.mono + std::max(kStallSettle, options_.period);
  for (const auto& stage : stages_) stage->note_late(now, late, discard_until);
  for (const auto& node : nodes_) node->note_late(now, late, discard_until);
}

void Hub::begin_opening_devices() noexcept {
  if (lifecycle_.enter(Lifecycle::kOpeningDevices, "files read; opening the devices of the nodes"))
    log_transition();
}

void Hub::derive_lifecycle() noexcept {
  if (lifecycle_.state() == Lifecycle::kStopping || nodes_.empty()) return;
  const NodeBase* worst = nodes_.front().get();
  for (const auto& node : nodes_) {
    if (severity(node->lifecycle().state()) > severity(worst->lifecycle().state())) worst = node.get();
  }
  const Lifecycle state = worst->lifecycle().state();
  const bool changed = state == Lifecycle::kOperational
                           ? lifecycle_.enter(state, "every node operational")
                           : lifecycle_.enter(state, "node '{}' {}: {}", worst->name(), lifecycle_name(state),
                                              worst->lifecycle().reason());
  if (changed) log_transition();
}

void Hub::log_transition() const noexcept {
  options_.log->info("hub '{}': lifecycle {} -> {} (transition {}): {}", options_.name,
                     lifecycle_name(lifecycle_.previous()), lifecycle_.name(), lifecycle_.transitions(),
                     lifecycle_.reason());
}

std::uint64_t Hub::states_deferred() const noexcept {
  std::uint64_t total = 0;
  for (const auto& node : nodes_) total += node->states_deferred();
  for (const auto& stage : stages_) total += stage->states_deferred();
  return total;
}

const NodeBase* Hub::hub_level_node() const noexcept {
  for (const auto& stage : stages_) {
    if (const NodeBase* node = stage->hub_level_node(); node != nullptr) return node;
  }
  return nullptr;
}

void Hub::enter_safe_state() noexcept {
  if (lifecycle_.enter(Lifecycle::kStopping, "stopping: outputs driven safe")) log_transition();
  for (const auto& node : nodes_) node->enter_safe_state();
}

void Hub::report_safe_state(const Instant& now) noexcept {
  for (const auto& stage : stages_) stage->after_safe_state(now);
}

}  // namespace hubrt::runtime
