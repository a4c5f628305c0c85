// CanBus on a bound, non-blocking CAN_RAW socket. Timeouts are poll() timeouts; the bus state
// comes from error frames, the interface flags and (on real controllers) libsocketcan.
#pragma once

#include <string>
#include <vector>

#include <linux/can.h>

#include "hubrt/base/time.h"
#include "hubrt/hal/can_bus.h"

namespace hubrt::hal::socketcan {

// Owns a file descriptor; closes it once.
class UniqueFd {
 public:
  UniqueFd() noexcept = default;
  explicit UniqueFd(int fd) noexcept : fd_(fd) {}
  ~UniqueFd();
  UniqueFd(UniqueFd&& other) noexcept : fd_(other.release()) {}
  UniqueFd& operator=(UniqueFd&& other) noexcept;
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;
  [[nodiscard]] int get() const noexcept { return fd_; }
  int release() noexcept;

 private:
  int fd_ = -1;
};

class SocketCanBus final : public CanBus {
 public:
  // `fd`: a CAN_RAW socket bound to `interface` (index `ifindex`), options already set, with
  // `filters` as its CAN_RAW_FILTER (kept: a re-bind must set them again).
  // `has_controller`: a real controller that reports state and counters over netlink (vcan has
  // none, and libsocketcan complains on stderr when asked).
  SocketCanBus(UniqueFd fd, std::string interface, unsigned ifindex, CanBusState initial_state,
               bool has_controller, std::vector<can_filter> filters);

 private:
  Status do_send(const CanFrame& frame, Duration timeout) noexcept override;
  Result<CanFrame> do_receive(Duration timeout) noexcept override;
  Status do_set_filters(std::span<const CanFilter> filters) noexcept override;
  CanBusStatus do_status() noexcept override;

  // Reads the interface flags (and, at most every kControllerQueryPeriod, the controller's state
  // and counters through libsocketcan); rebinds when the interface was re-created; clears the
  // socket's pending link error once the interface is up again.
  void refresh_link() noexcept;
  // After ENETDOWN / ENODEV / ENXIO: true when the link is in fact up again (the error was the
  // socket's stale report of an earlier down), so the call may be retried once.
  bool link_back_after_error() noexcept;
  // Consumes the error frames at the head of the receive queue (peeking, so that no data frame is
  // taken), so that status() and send() see a bus-off without waiting for the next receive().
  void take_error_frames() noexcept;
  void mark_down() noexcept;
  [[nodiscard]] bool unavailable() const noexcept { return status_.state >= CanBusState::kBusOff; }

  UniqueFd fd_;
  const std::string interface_;
  unsigned ifindex_;
  const bool has_controller_;
  CanBusStatus status_;
  Time next_controller_query_{};
  std::vector<can_filter> kernel_filters_;  // the filters in force; reused by set_filters
};

}  // namespace hubrt::hal::socketcan
