// Output lines. libgpiod 1.6 finds the chip and the line (and names a holder in errors); the
// request itself uses the GPIO character device's v1 ioctl that libgpiod uses underneath
// (GPIO_GET_LINEHANDLE_IOCTL, <linux/gpio.h>), because libgpiod v1 keeps a requested output's
// file descriptor private (gpiod_line_event_get_fd() serves event requests only) and the crash
// handler (crash_safe_outputs.h) must write to it with nothing but ioctl(2).
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include <gpiod.h>
#include <linux/gpio.h>
#include <sys/ioctl.h>

#include "hubrt/hal/linux/gpiod_lines.h"

#include "crash_safe_table.h"
#include "gpiod_chip.h"
#include "gpiod_errors.h"

namespace hubrt::hal {
namespace {

using gpiod_detail::line_io_status;
using gpiod_detail::LineHandle;

// With the active-low flag the kernel inverts what we write, so we deal in logical levels only.
class GpiodOutput final : public DigitalOutput {
 public:
  GpiodOutput(int fd, bool safe, bool active_low) noexcept
      : fd_(fd), safe_(safe), slot_(gpiod_detail::enter_crash_safe_output(fd, safe, active_low)) {}
  GpiodOutput(const GpiodOutput&) = delete;
  GpiodOutput& operator=(const GpiodOutput&) = delete;
  ~GpiodOutput() override {
    gpiod_detail::leave_crash_safe_output(slot_);  // before close: the number may be reused at once
    ::close(fd_);
  }

 private:
  Status do_write(bool active) noexcept override {
    gpiohandle_data data{};
    data.values[0] = active ? 1 : 0;
    if (::ioctl(fd_, GPIOHANDLE_SET_LINE_VALUES_IOCTL, &data) < 0) return line_io_status(errno);
    return Status::ok();
  }
  [[nodiscard]] bool do_safe_value() const noexcept override { return safe_; }

  int fd_;
  bool safe_;
  int slot_;  // in the crash-safe table; -1 when it was full
};

std::uint32_t request_flags(const DigitalOutputConfig& config) {
  std::uint32_t flags = GPIOHANDLE_REQUEST_OUTPUT;
  if (config.polarity == Polarity::kActiveLow) flags |= GPIOHANDLE_REQUEST_ACTIVE_LOW;
  if (config.bias_toward_safe) {
    const bool high = config.safe != (config.polarity == Polarity::kActiveLow);
    flags |= high ? GPIOHANDLE_REQUEST_BIAS_PULL_UP : GPIOHANDLE_REQUEST_BIAS_PULL_DOWN;
  }
  return flags;
}

// Requests the line as an output at `config.initial` and returns the request's descriptor.
Expected<int> request_output(const LineHandle& handle, const DigitalOutputConfig& config) {
  const std::string path = std::string("/dev/") + gpiod_chip_name(handle.chip());
  const int chip_fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
  if (chip_fd < 0) return gpiod_detail::request_error(handle, config.signal, 0, errno);
  gpiohandle_request request{};
  request.lineoffsets[0] = config.line;
  request.lines = 1;
  request.flags = request_flags(config);
  // The initial level goes into the request itself, so the line never shows another level.
  request.default_values[0] = config.initial ? 1 : 0;
  std::strncpy(request.consumer_label, kGpioConsumer, sizeof request.consumer_label - 1);
  const int result = ::ioctl(chip_fd, GPIO_GET_LINEHANDLE_IOCTL, &request);
  const int err = errno;
  ::close(chip_fd);
  if (result < 0)
    return gpiod_detail::request_error(handle, config.signal, static_cast<int>(request.flags), err);
  return request.fd;  // O_CLOEXEC (gpiolib-cdev's linehandle_create)
}

}  // namespace

Expected<std::unique_ptr<DigitalOutput>> open_gpiod_output(const DigitalOutputConfig& config) {
  auto line = gpiod_detail::find_line(config.signal, config.chip, config.line);
  if (!line) return std::move(line).error();
  auto fd = request_output(*line, config);
  if (!fd) return std::move(fd).error();
  return std::unique_ptr<DigitalOutput>(
      std::make_unique<GpiodOutput>(*fd, config.safe, config.polarity == Polarity::kActiveLow));
}

}  // namespace hubrt::hal
