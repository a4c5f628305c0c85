// hubd's guard against a second hub with the same name on the domain (rules in twin_rules.h):
//   - at start-up, before any device is opened, it watches discovery for a window and refuses to
//     run when another participant already writes one of this hub's State topics;
//   - while running, a stage puts "twin: ..." first in every node's error_list (and so in
//     /diagnostics) while a twin is there, and the later of the two hubs asks the runner to stop,
//     after which hubd drives the outputs safe and exits with status 1.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include <spdlog/logger.h>

#include "hubrt/assembly/twin_rules.h"
#include "hubrt/base/status.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/writer_watch.h"
#include "hubrt/runtime/hub.h"

namespace hubrt::assembly {

// Longest discovery window of the start-up check. Cyclone answers a new participant's SPDP
// announcement at once and the endpoints (SEDP) follow: on loopback (ASan build, loaded 2-core
// machine) the other hub's State writer showed up 2-6 ms after the watch started. 300 ms leaves
// margin for a LAN and a loaded Pi. The check waits this long only while a hub of an older hubrt
// (no identity in its USER_DATA) is on the domain; otherwise it ends once discovery has settled
// (kDefaultTwinCheckQuiet, StartupCheck in twin_rules.h). A hub that starts inside another's
// window is still caught by the running watch.
inline constexpr Duration kDefaultTwinCheckWindow = std::chrono::milliseconds(300);
// Discovery has settled when no participant was newly discovered for this long since the check
// began. Every participant answers a new one's SPDP at once (Cyclone 0.10
// src/core/ddsi/src/q_ddsi_discovery.c, respond_to_spdp: delay 0 with the default
// Internal/SPDPResponseMaxDelay of 0 ms, ddsi_cfgelems.h), and a twin hub is known from that
// answer alone (its identity is in its USER_DATA): on loopback the answers came within 1-3 ms
// (loaded 2-core machine); 15 ms leaves margin for a LAN and a busy Pi.
inline constexpr Duration kDefaultTwinCheckQuiet = std::chrono::milliseconds(15);
// How long a twin that left stays in error_list (see TwinMonitor).
inline constexpr Duration kTwinReportHold = std::chrono::seconds(10);

// Discovery side: the current twins of one hub, kept up to date from Cyclone's threads.
// Thread-safety: all members may be called from any thread.
class TwinWatch {
 public:
  // Starts watching writers of the State topics of hub `hub_name` under `ros_namespace` on
  // `participant` (which must outlive the watch). Errors: those of dds::WriterWatch::start.
  static Expected<std::unique_ptr<TwinWatch>> start(const dds::Participant& participant,
                                                    std::string ros_namespace, std::string hub_name,
                                                    std::shared_ptr<spdlog::logger> log);
  ~TwinWatch();
  TwinWatch(const TwinWatch&) = delete;
  TwinWatch& operator=(const TwinWatch&) = delete;

  // Watches discovery until StartupCheck (twin_rules.h) decides: at most `window`, less once
  // discovery has been `quiet`, both counted from start() — so the caller may do what needs no
  // verdict (DDS entities that publish nothing and are no State writer) between start() and this
  // call, and that work overlaps the window instead of adding to it. Errors: kBusy naming each
  // twin's topic, host and pid, when another participant writes this hub's States or announces
  // this hub's identity. Blocks the calling thread: call it before opening devices and before
  // creating any State writer, never from the cycle.
  Expected<void> check_at_start(Duration window, Duration quiet = kDefaultTwinCheckQuiet) const;

  // Copies the current twins into `out` when they changed since `seen` (then updates `seen`).
  // Allocation-free: for the cycle.
  void copy_if_changed(std::uint64_t& seen, TwinSnapshot& out) const noexcept;

 private:
  TwinWatch(std::string hub_name, std::string identity, std::shared_ptr<spdlog::logger> log, Time started)
      : hub_name_(std::move(hub_name)),
        identity_(std::move(identity)),
        log_(std::move(log)),
        started_(started) {}
  void changed(const std::vector<dds::WatchedWriter>& writers);

  std::string hub_name_;
  std::string identity_;  // "<ros_namespace>/<hub>", as hub_user_data() announces it
  std::shared_ptr<spdlog::logger> log_;
  Time started_;  // steady clock, when discovery began to be watched: the start-up check's begin
  mutable std::mutex mutex_;
  TwinSnapshot snapshot_;
  std::atomic<std::uint64_t> generation_{0};
  bool had_twins_ = false;                     // changed() only (WriterWatch never runs it twice at once)
  std::unique_ptr<dds::WriterWatch> writers_;  // last: its callbacks use the members above
};

// The cycle side: sets the hub's alerts each cycle and, when this hub is the later one, calls
// `request_stop` once, after the cycle that published the twin report.
class TwinStage final : public runtime::CycleStage {
 public:
  // `watch` and `alerts` must outlive the stage.
  TwinStage(const TwinWatch& watch, runtime::HubAlerts& alerts, HubStamp self,
            std::function<void()> request_stop)
      : watch_(watch),
        alerts_(alerts),
        monitor_(self, kTwinReportHold),
        request_stop_(std::move(request_stop)) {}

  void before_nodes(const Instant& now) noexcept override;
  void after_nodes(const Instant& now, bool publish_all, bool took_effect) noexcept override;

  // After the runner returned: true when this hub stopped because an earlier hub runs.
  [[nodiscard]] bool yielded() const noexcept { return stop_requested_; }
  // "another hub with the same name ... started earlier: ..." (allocates).
  [[nodiscard]] std::string yield_message() const;

 private:
  const TwinWatch& watch_;
  runtime::HubAlerts& alerts_;
  TwinMonitor monitor_;
  std::function<void()> request_stop_;
  std::uint64_t seen_ = 0;
  TwinSnapshot snapshot_{};
  bool stop_requested_ = false;
};

}  // namespace hubrt::assembly
