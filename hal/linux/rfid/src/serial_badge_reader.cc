// A serial ASCII RFID reader: each badge is a line of text ended by a terminator byte (CR or LF;
// the other one, which many readers send too, is ignored). The port is put in raw mode (termios
// cfmakeraw: no echo, no line editing, 8N1) and read without blocking: poll(2) with a zero
// timeout says whether bytes are waiting or the line hung up (POLLHUP: a USB adapter unplugged,
// or for a pty the other side closed); read(2) takes what is there.
#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <system_error>

#include <fmt/format.h>

#include "hubrt/hal/common/badge_line.h"

#include "badge_reader_kinds.h"

namespace hubrt::hal::rfid {
namespace {

bool speed_for(std::uint32_t baud, speed_t& speed) noexcept {
  switch (baud) {
    case 1200:
      speed = B1200;
      return true;
    case 2400:
      speed = B2400;
      return true;
    case 4800:
      speed = B4800;
      return true;
    case 9600:
      speed = B9600;
      return true;
    case 19200:
      speed = B19200;
      return true;
    case 38400:
      speed = B38400;
      return true;
    case 57600:
      speed = B57600;
      return true;
    case 115200:
      speed = B115200;
      return true;
    default:
      return false;
  }
}

class SerialBadgeReader final : public BadgeReader {
 public:
  SerialBadgeReader(int fd, const BadgeReaderConfig& config) noexcept
      : fd_(fd), terminator_(config.terminator), line_(config.timeout) {}
  ~SerialBadgeReader() override { ::close(fd_); }
  SerialBadgeReader(const SerialBadgeReader&) = delete;
  SerialBadgeReader& operator=(const SerialBadgeReader&) = delete;

 private:
  Result<bool> do_poll(BadgeRead& out, Time now) noexcept override {
    // Bytes read earlier that follow a finished badge come first.
    if (take_pending(out, now)) return true;
    if (line_.expire(out, now)) return true;
    for (int i = 0; i < kMaxReadsPerPoll; ++i) {
      pollfd waiting{fd_, POLLIN, 0};
      if (::poll(&waiting, 1, 0) < 0) return errno == EINTR ? Result<bool>(false) : Status(ErrorCode::kIo);
      const bool hung_up = (waiting.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0;
      if ((waiting.revents & POLLIN) == 0 && !hung_up) return false;
      const ssize_t n = ::read(fd_, buffer_.data(), buffer_.size());
      if (n > 0) {
        pending_begin_ = 0;
        pending_end_ = static_cast<std::size_t>(n);
        if (take_pending(out, now)) return true;
        continue;
      }
      const int err = n < 0 ? errno : 0;
      if (!hung_up && (n == 0 || err == EAGAIN || err == EINTR)) return false;
      // Hung up with nothing left to read, or EIO/ENODEV (the adapter went away): gone.
      line_.clear();
      return (hung_up || err == EIO || err == ENODEV || err == ENXIO) ? Status(ErrorCode::kUnavailable)
                                                                      : Status(ErrorCode::kIo);
    }
    return false;
  }

  // Feeds the bytes read but not used yet; true when they finished a badge (the rest stays).
  bool take_pending(BadgeRead& out, Time now) noexcept {
    while (pending_begin_ < pending_end_) {
      const char c = buffer_[pending_begin_++];
      if (c == terminator_) {
        if (line_.end(out, now)) return true;
      } else if (c == '\r' || c == '\n') {
        continue;  // the other half of a CR LF pair
      } else {
        line_.add(c, now);
      }
    }
    return false;
  }

  static constexpr int kMaxReadsPerPoll = 16;
  int fd_;
  char terminator_;
  BadgeLineAssembler line_;
  std::array<char, 64> buffer_{};
  std::size_t pending_begin_ = 0;
  std::size_t pending_end_ = 0;
};

}  // namespace

Expected<std::unique_ptr<BadgeReader>> open_serial_badge_reader(const BadgeReaderConfig& config) {
  const auto fail = [&](ErrorCode code, std::string_view why) {
    return make_error(code, fmt::format("{}: serial port {}: {}", config.reader, config.device, why));
  };
  speed_t speed = B0;
  if (!speed_for(config.baud, speed)) {
    return fail(ErrorCode::kInvalidArgument, fmt::format("{} is not a standard baud rate", config.baud));
  }
  const int fd = ::open(config.device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    const ErrorCode code = err == ENOENT || err == ENODEV || err == ENXIO ? ErrorCode::kNotFound
                           : err == EACCES || err == EPERM                ? ErrorCode::kPermissionDenied
                           : err == EBUSY                                 ? ErrorCode::kBusy
                                                                          : ErrorCode::kIo;
    return fail(code, err == EACCES ? "permission denied (add the hub's user to group dialout)"
                                    : std::generic_category().message(err));
  }
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) {
    const int err = errno;
    ::close(fd);
    return fail(ErrorCode::kInvalidArgument,
                fmt::format("not a terminal ({})", std::generic_category().message(err)));
  }
  ::cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (::cfsetispeed(&tio, speed) != 0 || ::cfsetospeed(&tio, speed) != 0 ||
      ::tcsetattr(fd, TCSANOW, &tio) != 0) {
    const int err = errno;
    ::close(fd);
    return fail(ErrorCode::kIo,
                fmt::format("cannot configure it ({})", std::generic_category().message(err)));
  }
  // Whatever waited in the port from before (a badge shown while no hub ran) is stale.
  ::tcflush(fd, TCIFLUSH);
  return std::unique_ptr<BadgeReader>(new SerialBadgeReader(fd, config));
}

}  // namespace hubrt::hal::rfid
