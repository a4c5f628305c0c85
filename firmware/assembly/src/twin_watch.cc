#include "hubrt/assembly/twin_watch.h"

#include <algorithm>
#include <thread>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace hubrt::assembly {
namespace {

// The start-up check's clock (steady: a wall clock step must not end or stretch the window).
Time steady_now() {
  return Time(std::chrono::steady_clock::now().time_since_epoch());
}

// Longest sleep between two looks at discovery during the start-up check. A participant
// discovered while the check sleeps counts from when it is seen, so a longer step only makes the
// check later, never laxer; this step keeps that lateness (and so the verdict's) under 0.5 ms.
constexpr Duration kStartupPollStep = std::chrono::microseconds(500);
std::string describe(const TwinPeer& peer) {
  runtime::TextBuffer<128> origin;
  describe_origin(peer, origin);
  std::string text = fmt::format("{} from {}", peer.topic.view(), origin.view());
  if (peer.topics > 1) text += fmt::format(" (and {} more State topics)", peer.topics - 1);
  return text;
}

}  // namespace

Expected<std::unique_ptr<TwinWatch>> TwinWatch::start(const dds::Participant& participant,
                                                      std::string ros_namespace, std::string hub_name,
                                                      std::shared_ptr<spdlog::logger> log) {
  std::string identity = fmt::format("{}/{}", ros_namespace, hub_name);
  std::unique_ptr<TwinWatch> watch(new TwinWatch(
      hub_name, std::move(identity), log ? std::move(log) : spdlog::default_logger(), steady_now()));
  TwinWatch* self = watch.get();
  auto writers = dds::WriterWatch::start(
      participant,
      [ns = std::move(ros_namespace), hub = std::move(hub_name)](std::string_view topic) {
        return is_own_state_topic(topic, ns, hub);
      },
      [self](const std::vector<dds::WatchedWriter>& list) { self->changed(list); });
  if (!writers) return std::move(writers).error();
  watch->writers_ = std::move(*writers);
  return watch;
}

TwinWatch::~TwinWatch() {
  writers_.reset();  // no callback runs after this
}

void TwinWatch::changed(const std::vector<dds::WatchedWriter>& writers) {
  TwinSnapshot snapshot = summarize_twins(writers);
  {
    const std::lock_guard lock(mutex_);
    snapshot.sightings = snapshot_.sightings + (snapshot.count > 0 ? 1 : 0);
    snapshot.last = snapshot.count > 0 ? snapshot.peers[0] : snapshot_.last;
    snapshot_ = snapshot;
  }
  generation_.fetch_add(1, std::memory_order_release);
  // Logged here, on Cyclone's thread, rather than in the cycle (logging allocates).
  if (snapshot.count == 0) {
    if (had_twins_)
      log_->info("twin: no other participant publishes the States of hub '{}' any more", hub_name_);
    had_twins_ = false;
    return;
  }
  had_twins_ = true;
  for (std::size_t i = 0; i < snapshot.count; ++i) {
    log_->error("twin: another hub publishes {}", describe(snapshot.peers[i]));
  }
}

Expected<void> TwinWatch::check_at_start(Duration window, Duration quiet) const {
  log_->debug(
      "twin: watching discovery (at most {} ms, settled after {} ms quiet) for another participant "
      "publishing the States of hub '{}'",
      std::chrono::duration_cast<std::chrono::milliseconds>(window).count(),
      std::chrono::duration_cast<std::chrono::milliseconds>(quiet).count(), hub_name_);
  // Polled rather than waited on: the window is short and this runs once, before the cycle.
  // Counted from start(): what the caller did since overlapped the window.
  const Time begin = started_;
  StartupCheck check(identity_, begin, window, quiet);
  std::uint64_t seen = 0;
  TwinSnapshot snapshot;
  for (;;) {
    copy_if_changed(seen, snapshot);
    const Time now = steady_now();
    const std::uint64_t discovered = writers_->participants_discovered();
    const Time discovered_at(writers_->last_discovered_at());
    const StartupVerdict verdict =
        check.update(writers_->participants(), discovered, discovered_at, snapshot.count, now);
    if (verdict == StartupVerdict::kAlone) {
      log_->debug("twin: none after {:.1f} ms of discovery", to_seconds(now - begin) * 1e3);
      return {};
    }
    if (verdict == StartupVerdict::kTwin) break;
    // Until the rule can decide (StartupCheck::decides_by), looking at discovery meanwhile.
    std::this_thread::sleep_for(std::min(kStartupPollStep, check.decides_by() - now));
  }
  // A twin by identity alone: its writer names it (StartupCheck::waits_for_name).
  while (check.waits_for_name(snapshot.count, steady_now())) {
    std::this_thread::sleep_for(kStartupPollStep);
    copy_if_changed(seen, snapshot);
  }
  std::string twins;
  for (std::size_t i = 0; i < snapshot.count; ++i) {
    twins += fmt::format("{}{}", i == 0 ? "" : "; ", describe(snapshot.peers[i]));
  }
  if (snapshot.more > 0) twins += fmt::format("; and {} more", snapshot.more);
  if (snapshot.count == 0) {
    // Known by its identity (SPDP) before any of its writers arrived.
    TwinPeer peer;
    peer.participant = check.claimant();
    runtime::TextBuffer<128> origin;
    describe_origin(peer, origin);
    twins = fmt::format("a hub announcing the same identity '{}' ({})", identity_, origin.view());
  }
  return make_error(
      ErrorCode::kBusy,
      fmt::format("twin: another hub already publishes the States of hub '{}': {}; refusing to "
                  "start (no device opened, no output touched): stop the other hub, or give this "
                  "one another name (--name)",
                  hub_name_, twins));
}

void TwinWatch::copy_if_changed(std::uint64_t& seen, TwinSnapshot& out) const noexcept {
  const std::uint64_t generation = generation_.load(std::memory_order_acquire);
  if (generation == seen) return;
  const std::lock_guard lock(mutex_);
  out = snapshot_;
  seen = generation;
}

void TwinStage::before_nodes(const Instant& now) noexcept {
  watch_.copy_if_changed(seen_, snapshot_);
  monitor_.update(snapshot_, now.mono, alerts_);
}

void TwinStage::after_nodes(const Instant& /*now*/, bool publish_all, bool /*took_effect*/) noexcept {
  // Only after a periodic cycle: every node's State with the twin report has gone out.
  if (!publish_all || stop_requested_ || !monitor_.must_yield()) return;
  stop_requested_ = true;
  if (request_stop_) request_stop_();
}

std::string TwinStage::yield_message() const {
  return fmt::format(
      "twin: another hub publishes {} and started earlier than this one: this one is the later "
      "and stops",
      describe(monitor_.yielded_to()));
}

}  // namespace hubrt::assembly
