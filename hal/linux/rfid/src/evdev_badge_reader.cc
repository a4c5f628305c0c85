// A HID keyboard-wedge RFID reader through libevdev. libevdev's contract, as its documentation
// (https://www.freedesktop.org/software/libevdev/doc/latest/group__events.html) gives it:
// libevdev_next_event() returns LIBEVDEV_READ_STATUS_SUCCESS with an event, -EAGAIN when none is
// waiting (the fd is non-blocking), LIBEVDEV_READ_STATUS_SYNC after the kernel dropped events
// (SYN_DROPPED; the events that resync the state are then read with LIBEVDEV_READ_FLAG_SYNC until
// -EAGAIN), and a negative errno otherwise (-ENODEV once the device is unplugged).
// libevdev_grab(LIBEVDEV_GRAB) is the EVIOCGRAB ioctl: while grabbed, no other reader of the
// device (the console, X, a login prompt) sees the badge's keystrokes.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

#include <fmt/format.h>
#include <libevdev/libevdev.h>

#include "badge_reader_kinds.h"
#include "key_decoder.h"

namespace hubrt::hal::rfid {
namespace {

ErrorCode open_error(int err) noexcept {
  switch (err) {
    case ENOENT:
    case ENODEV:
    case ENXIO:
      return ErrorCode::kNotFound;
    case EACCES:
    case EPERM:
      return ErrorCode::kPermissionDenied;
    case EBUSY:
      return ErrorCode::kBusy;
    default:
      return ErrorCode::kIo;
  }
}

class EvdevBadgeReader final : public BadgeReader {
 public:
  EvdevBadgeReader(int fd, libevdev* dev, Duration timeout) noexcept : fd_(fd), dev_(dev), keys_(timeout) {}
  ~EvdevBadgeReader() override {
    // Closing the fd also ends the grab (EVIOCGRAB is per open file).
    libevdev_free(dev_);
    ::close(fd_);
  }
  EvdevBadgeReader(const EvdevBadgeReader&) = delete;
  EvdevBadgeReader& operator=(const EvdevBadgeReader&) = delete;

 private:
  Result<bool> do_poll(BadgeRead& out, Time now) noexcept override {
    if (keys_.expire(out, now)) return true;
    // Bounded: a reader that floods events cannot hold the cycle; the rest waits in the kernel.
    for (int i = 0; i < kMaxEventsPerPoll; ++i) {
      input_event ev{};
      const int rc = libevdev_next_event(dev_, LIBEVDEV_READ_FLAG_NORMAL, &ev);
      if (rc == -EAGAIN) return false;
      if (rc == LIBEVDEV_READ_STATUS_SYNC) {
        keys_.events_lost(now);
        drain_sync();
        continue;
      }
      if (rc == -ENODEV) {
        keys_.clear();
        return Status(ErrorCode::kUnavailable);
      }
      if (rc < 0) return Status(ErrorCode::kIo);
      if (keys_.feed(ev.type, ev.code, ev.value, out, now)) return true;
    }
    return false;
  }

  void drain_sync() noexcept {
    input_event ev{};
    for (int i = 0; i < kMaxEventsPerPoll; ++i) {
      if (libevdev_next_event(dev_, LIBEVDEV_READ_FLAG_SYNC, &ev) != LIBEVDEV_READ_STATUS_SYNC) return;
    }
  }

  static constexpr int kMaxEventsPerPoll = 256;
  int fd_;
  libevdev* dev_;
  KeyDecoder keys_;
};

}  // namespace

Expected<std::unique_ptr<BadgeReader>> open_evdev_badge_reader(const BadgeReaderConfig& config) {
  const auto fail = [&](ErrorCode code, std::string_view why) {
    return make_error(code, fmt::format("{}: input device {}: {}", config.reader, config.device, why));
  };
  const int fd = ::open(config.device.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    return fail(open_error(err), err == EACCES ? "permission denied (add the hub's user to group input, "
                                                 "or a udev rule: docs/deploy.md)"
                                               : std::generic_category().message(err));
  }
  libevdev* dev = nullptr;
  if (const int rc = libevdev_new_from_fd(fd, &dev); rc < 0) {
    ::close(fd);
    return fail(ErrorCode::kInvalidArgument,
                fmt::format("not an input event device ({})", std::generic_category().message(-rc)));
  }
  if (!libevdev_has_event_code(dev, EV_KEY, KEY_ENTER)) {
    libevdev_free(dev);
    ::close(fd);
    return fail(ErrorCode::kInvalidArgument,
                "has no Enter key: not a keyboard-wedge reader (check the by-id path)");
  }
  if (config.grab) {
    if (const int rc = libevdev_grab(dev, LIBEVDEV_GRAB); rc < 0) {
      libevdev_free(dev);
      ::close(fd);
      return fail(open_error(-rc), fmt::format("cannot grab it (EVIOCGRAB: {}): another process holds it",
                                               std::generic_category().message(-rc)));
    }
  }
  return std::unique_ptr<BadgeReader>(new EvdevBadgeReader(fd, dev, config.timeout));
}

}  // namespace hubrt::hal::rfid
