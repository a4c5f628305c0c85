#include <cerrno>

#include <gpiod.h>

#include "hubrt/hal/linux/gpiod_lines.h"

#include "gpiod_chip.h"
#include "gpiod_errors.h"

namespace hubrt::hal {
namespace {

using gpiod_detail::line_io_status;
using gpiod_detail::LineHandle;

// With the active-low flag the kernel inverts what we write, so we deal in logical levels only.
class GpiodOutput final : public DigitalOutput {
 public:
  GpiodOutput(LineHandle line, bool safe) noexcept : line_(std::move(line)), safe_(safe) {}

 private:
  Status do_write(bool active) noexcept override {
    errno = 0;
    if (gpiod_line_set_value(line_.line(), active ? 1 : 0) < 0) return line_io_status(errno);
    return Status::ok();
  }
  [[nodiscard]] bool do_safe_value() const noexcept override { return safe_; }

  LineHandle line_;
  bool safe_;
};

}  // namespace

Expected<std::unique_ptr<DigitalOutput>> open_gpiod_output(const DigitalOutputConfig& config) {
  auto line = gpiod_detail::find_line(config.signal, config.chip, config.line);
  if (!line) return std::move(line).error();
  const int flags = config.polarity == Polarity::kActiveLow ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
  // The initial level goes into the request itself, so the line never shows another level.
  auto requested = gpiod_detail::request_line(*line, config.signal, GPIOD_LINE_REQUEST_DIRECTION_OUTPUT,
                                              flags, config.initial ? 1 : 0);
  if (!requested) return std::move(requested).error();
  return std::unique_ptr<DigitalOutput>(std::make_unique<GpiodOutput>(std::move(*line), config.safe));
}

}  // namespace hubrt::hal
