#include "socketcan_bus.h"

#include <libsocketcan.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstring>
#include <utility>

#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>

#include "socketcan_codec.h"

namespace hubrt::hal::socketcan {
namespace {

using Steady = std::chrono::steady_clock;

// libsocketcan opens a netlink socket per query: often enough to follow the controller, rarely
// enough not to matter when status() is called every cycle.
constexpr auto kControllerQueryPeriod = std::chrono::milliseconds(250);
// POLLOUT does not report room in the driver's queue (ENOBUFS): back off this long and retry.
constexpr auto kNoBufferBackoff = std::chrono::milliseconds(1);
// Longer timeouts are cut to this so that deadline arithmetic cannot overflow.
constexpr Duration kMaxWait = std::chrono::hours(24);

Steady::time_point deadline_after(Duration timeout) noexcept {
  return Steady::now() + std::clamp(timeout, Duration::zero(), kMaxWait);
}

// Milliseconds for poll(), rounded up so that a wait never ends before its deadline.
int poll_ms(Steady::duration remaining) noexcept {
  const auto ms = std::chrono::ceil<std::chrono::milliseconds>(remaining).count();
  return static_cast<int>(std::clamp<std::int64_t>(ms, 0, INT_MAX));
}

bool is_link_gone(int err) noexcept {
  return err == ENETDOWN || err == ENODEV || err == ENXIO;
}

}  // namespace

UniqueFd::~UniqueFd() {
  if (fd_ >= 0) ::close(fd_);
}

UniqueFd& UniqueFd::operator=(UniqueFd&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.release();
  }
  return *this;
}

int UniqueFd::release() noexcept {
  return std::exchange(fd_, -1);
}

SocketCanBus::SocketCanBus(UniqueFd fd, std::string interface, unsigned ifindex, CanBusState initial_state,
                           bool has_controller, std::vector<can_filter> filters)
    : fd_(std::move(fd)),
      interface_(std::move(interface)),
      ifindex_(ifindex),
      has_controller_(has_controller),
      kernel_filters_(std::move(filters)) {
  status_.state = initial_state;
}

Status SocketCanBus::do_send(const CanFrame& frame, Duration timeout) noexcept {
  can_frame out{};
  if (const Status valid = to_kernel_frame(frame, out); !valid.is_ok()) return valid;
  if (unavailable()) {
    refresh_link();
    take_error_frames();  // a restart report ends bus-off
    if (unavailable()) return Status(ErrorCode::kUnavailable);
  }
  const auto deadline = deadline_after(timeout);
  bool retried = false;
  for (;;) {
    const ssize_t n = ::send(fd_.get(), &out, sizeof out, MSG_DONTWAIT | MSG_NOSIGNAL);
    if (n == static_cast<ssize_t>(sizeof out)) return Status::ok();
    if (n >= 0) return Status(ErrorCode::kIo);
    const int err = errno;
    if (err == EINTR) continue;
    if (is_link_gone(err)) {
      if (!retried && link_back_after_error()) {
        retried = true;
        continue;
      }
      return Status(ErrorCode::kUnavailable);
    }
    if (err != EAGAIN && err != EWOULDBLOCK && err != ENOBUFS) return Status(ErrorCode::kIo);
    // A full transmit queue is what a bus-off controller looks like from here: say so rather
    // than wait out the timeout.
    take_error_frames();
    if (unavailable()) return Status(ErrorCode::kUnavailable);
    const auto remaining = deadline - Steady::now();
    if (remaining <= Steady::duration::zero()) return Status(ErrorCode::kTimeout);
    if (err == ENOBUFS) {
      ::poll(nullptr, 0, poll_ms(std::min<Steady::duration>(remaining, kNoBufferBackoff)));
    } else {
      pollfd p{fd_.get(), POLLOUT, 0};
      ::poll(&p, 1, poll_ms(remaining));
    }
  }
}

Result<CanFrame> SocketCanBus::do_receive(Duration timeout) noexcept {
  const auto deadline = deadline_after(timeout);
  bool retried = false;
  for (;;) {
    can_frame in{};
    iovec iov{&in, sizeof in};
    alignas(cmsghdr) std::array<char, CMSG_SPACE(sizeof(std::uint32_t))> control{};
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control.data();
    msg.msg_controllen = control.size();
    const ssize_t n = ::recvmsg(fd_.get(), &msg, MSG_DONTWAIT);
    if (n == static_cast<ssize_t>(sizeof in)) {
      for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
        if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
          std::memcpy(&status_.rx_dropped, CMSG_DATA(c), sizeof status_.rx_dropped);
        }
      }
      if ((in.can_id & CAN_ERR_FLAG) != 0) {
        apply_error_frame(in, status_);
        if (unavailable()) return Status(ErrorCode::kUnavailable);
        continue;
      }
      // A frame arrived: whatever we thought, the link is up.
      if (status_.state == CanBusState::kDown) status_.state = CanBusState::kErrorActive;
      return from_kernel_frame(in);
    }
    if (n >= 0) return Status(ErrorCode::kIo);  // a short or oversized frame: not classic CAN
    const int err = errno;
    if (err == EINTR) continue;
    if (is_link_gone(err)) {
      if (!retried && link_back_after_error()) {
        retried = true;
        continue;
      }
      return Status(ErrorCode::kUnavailable);
    }
    if (err != EAGAIN && err != EWOULDBLOCK) return Status(ErrorCode::kIo);
    const auto remaining = deadline - Steady::now();
    if (unavailable() || remaining <= Steady::duration::zero()) {
      // Nothing queued: before reporting, look whether the link went (or came back).
      refresh_link();
      if (unavailable()) return Status(ErrorCode::kUnavailable);
      if (remaining <= Steady::duration::zero()) return Status(ErrorCode::kTimeout);
    }
    pollfd p{fd_.get(), POLLIN, 0};
    ::poll(&p, 1, poll_ms(remaining));
  }
}

Status SocketCanBus::do_set_filters(std::span<const CanFilter> filters) noexcept {
  if (const Status valid = to_kernel_filters(filters, kernel_filters_); !valid.is_ok()) return valid;
  const auto size = static_cast<socklen_t>(kernel_filters_.size() * sizeof(can_filter));
  if (::setsockopt(fd_.get(), SOL_CAN_RAW, CAN_RAW_FILTER, kernel_filters_.data(), size) != 0) {
    return Status(errno == EINVAL ? ErrorCode::kInvalidArgument : ErrorCode::kIo);
  }
  return Status::ok();
}

CanBusStatus SocketCanBus::do_status() noexcept {
  refresh_link();
  take_error_frames();
  return status_;
}

void SocketCanBus::take_error_frames() noexcept {
  for (;;) {
    can_frame head{};
    if (::recv(fd_.get(), &head, sizeof head, MSG_PEEK | MSG_DONTWAIT) != static_cast<ssize_t>(sizeof head) ||
        (head.can_id & CAN_ERR_FLAG) == 0) {
      return;
    }
    if (::recv(fd_.get(), &head, sizeof head, MSG_DONTWAIT) != static_cast<ssize_t>(sizeof head)) return;
    apply_error_frame(head, status_);
  }
}

void SocketCanBus::mark_down() noexcept {
  status_.state = CanBusState::kDown;
}

bool SocketCanBus::link_back_after_error() noexcept {
  mark_down();
  refresh_link();
  return !unavailable();
}

void SocketCanBus::refresh_link() noexcept {
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, interface_.c_str(), IFNAMSIZ - 1);
  if (::ioctl(fd_.get(), SIOCGIFFLAGS, &ifr) != 0 || (ifr.ifr_flags & IFF_UP) == 0) {
    mark_down();
    return;
  }
  // Up. A re-created interface (vcan deleted and added, USB adapter replugged) has a new index:
  // a raw socket may be bound again. The kernel dropped the socket's receive filters when the old
  // interface went (net/can/raw.c, raw_notify() on NETDEV_UNREGISTER: ro->count = 0), so without
  // setting them again the re-bound socket would receive nothing; set before bind(), which then
  // registers them (raw_bind() -> raw_enable_allfilters()).
  const unsigned index = ::if_nametoindex(interface_.c_str());
  if (index != 0 && index != ifindex_) {
    const auto filter_bytes = static_cast<socklen_t>(kernel_filters_.size() * sizeof(can_filter));
    ::setsockopt(fd_.get(), SOL_CAN_RAW, CAN_RAW_FILTER, kernel_filters_.data(), filter_bytes);
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = static_cast<int>(index);
    if (::bind(fd_.get(), reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0) ifindex_ = index;
  }
  if (status_.state == CanBusState::kDown) {
    // The kernel reported the down (or removal) as a pending socket error (ENETDOWN, ENODEV);
    // read it now, or it would fail the first call after the link came back.
    int pending = 0;
    socklen_t len = sizeof pending;
    ::getsockopt(fd_.get(), SOL_SOCKET, SO_ERROR, &pending, &len);
    status_.state = CanBusState::kErrorActive;
  }
  if (!has_controller_) return;
  const Time now = std::chrono::time_point_cast<Duration>(Steady::now());
  if (now < next_controller_query_) return;
  next_controller_query_ = now + kControllerQueryPeriod;
  int state = 0;
  if (can_get_state(interface_.c_str(), &state) == 0) status_.state = from_netlink_state(state);
  can_berr_counter counters{};
  if (can_get_berr_counter(interface_.c_str(), &counters) == 0) {
    status_.tx_errors = counters.txerr;
    status_.rx_errors = counters.rxerr;
  }
}

}  // namespace hubrt::hal::socketcan
