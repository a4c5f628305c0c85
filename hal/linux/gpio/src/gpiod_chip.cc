#include "gpiod_chip.h"

#include <cerrno>
#include <vector>

#include <fmt/format.h>

#include "hubrt/hal/common/gpio_chip_selector.h"
#include "hubrt/hal/linux/gpiod_lines.h"

#include "gpiod_errors.h"

namespace hubrt::hal {
namespace gpiod_detail {
namespace {

std::string describe_chip(gpiod_chip* chip) {
  return fmt::format("{} [{}]", gpiod_chip_name(chip), gpiod_chip_label(chip));
}

// What to add to a "chip not found" message: the chips that do exist.
std::string chips_present() {
  auto chips = list_gpio_chips();
  if (!chips) return fmt::format("could not list the GPIO chips: {}", chips.error().message);
  if (chips->empty()) {
    return "no GPIO chips present (no /dev/gpiochip*: kernel without GPIO support (CONFIG_GPIOLIB) "
           "or the GPIO driver is not loaded)";
  }
  std::string out = "chips present:";
  for (const GpioChipInfo& info : *chips) {
    out += fmt::format(" {} [{}] ({} lines),", info.name, info.label, info.num_lines);
  }
  out.pop_back();
  return out;
}

Error chip_open_error(std::string_view signal, const std::string& chip, int err) {
  const GpioChipSelectorKind kind = classify_gpio_chip(chip);
  switch (err) {
    case ENOENT:
      return make_error(ErrorCode::kNotFound, fmt::format("{}: GPIO chip with {} '{}' not found; {}", signal,
                                                          to_string(kind), chip, chips_present()));
    case EACCES:
    case EPERM:
      return make_error(ErrorCode::kPermissionDenied,
                        fmt::format("{}: permission denied opening GPIO chip '{}' (the user needs read/write "
                                    "access to /dev/gpiochip*, e.g. membership of group 'gpio')",
                                    signal, chip));
    case ENOTTY:
    case ENODEV:
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: '{}' is not a GPIO character device", signal, chip));
    default:
      return make_error(ErrorCode::kIo,
                        fmt::format("{}: cannot open GPIO chip '{}': {}", signal, chip, errno_text(err)));
  }
}

gpiod_chip* open_chip(const std::string& chip) {
  switch (classify_gpio_chip(chip)) {
    case GpioChipSelectorKind::kPath:
      return gpiod_chip_open(chip.c_str());
    case GpioChipSelectorKind::kName:
      return gpiod_chip_open_by_name(chip.c_str());
    case GpioChipSelectorKind::kLabel:
      return gpiod_chip_open_by_label(chip.c_str());
  }
  return nullptr;
}

}  // namespace

LineHandle::LineHandle(ChipHandle chip, gpiod_line* line, std::string description) noexcept
    : chip_(std::move(chip)), line_(line), description_(std::move(description)) {}

LineHandle::LineHandle(LineHandle&& other) noexcept
    : chip_(std::move(other.chip_)), line_(other.line_), description_(std::move(other.description_)) {
  other.line_ = nullptr;
}

LineHandle::~LineHandle() {
  if (line_ != nullptr && gpiod_line_is_requested(line_)) gpiod_line_release(line_);
}

Expected<LineHandle> find_line(std::string_view signal, const std::string& chip, unsigned offset) {
  if (chip.empty())
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: no GPIO chip given", signal));
  errno = 0;
  ChipHandle handle(open_chip(chip));
  if (!handle) return chip_open_error(signal, chip, errno);
  const unsigned num_lines = gpiod_chip_num_lines(handle.get());
  if (offset >= num_lines) {
    return make_error(
        ErrorCode::kOutOfRange,
        fmt::format("{}: line {} is beyond GPIO chip {}, which has {} lines (0..{})", signal, offset,
                    describe_chip(handle.get()), num_lines, num_lines == 0 ? 0 : num_lines - 1));
  }
  errno = 0;
  gpiod_line* line = gpiod_chip_get_line(handle.get(), offset);
  if (line == nullptr) {
    const int err = errno;
    return make_error(ErrorCode::kIo, fmt::format("{}: cannot read line {} of GPIO chip {}: {}", signal,
                                                  offset, describe_chip(handle.get()), errno_text(err)));
  }
  std::string description = fmt::format("line {} of {}", offset, describe_chip(handle.get()));
  return LineHandle(std::move(handle), line, std::move(description));
}

Expected<void> request_line(const LineHandle& handle, std::string_view signal, int request_type, int flags,
                            int default_value) {
  const gpiod_line_request_config config{kGpioConsumer, request_type, flags};
  errno = 0;
  if (gpiod_line_request(handle.line(), &config, default_value) == 0) return {};
  return request_error(handle, signal, flags, errno);
}

Error request_error(const LineHandle& handle, std::string_view signal, int flags, int err) {
  switch (err) {
    case EBUSY: {
      // The cached line info is from when we looked the line up: refresh it to name the holder.
      const char* holder =
          gpiod_line_update(handle.line()) == 0 ? gpiod_line_consumer(handle.line()) : nullptr;
      return make_error(ErrorCode::kBusy,
                        fmt::format("{}: {} is busy, held by {}", signal, handle.description(),
                                    holder != nullptr ? fmt::format("'{}'", holder) : "an unnamed consumer"));
    }
    case EACCES:
    case EPERM:
      return make_error(ErrorCode::kPermissionDenied,
                        fmt::format("{}: permission denied requesting {}", signal, handle.description()));
    case EINVAL:
    case EOPNOTSUPP:
      return make_error(
          ErrorCode::kInvalidArgument,
          fmt::format("{}: the kernel refused the request for {} (flags {:#x}): {} (bias flags need "
                      "Linux 5.5 or later and a driver that supports them)",
                      signal, handle.description(), flags, errno_text(err)));
    default:
      return make_error(ErrorCode::kIo, fmt::format("{}: cannot request {}: {}", signal, handle.description(),
                                                    errno_text(err)));
  }
}

}  // namespace gpiod_detail

Expected<std::vector<GpioChipInfo>> list_gpio_chips() {
  errno = 0;
  gpiod_chip_iter* iter = gpiod_chip_iter_new();
  if (iter == nullptr) {
    const int err = errno;
    return make_error(err == EACCES || err == EPERM ? ErrorCode::kPermissionDenied : ErrorCode::kIo,
                      fmt::format("cannot scan the GPIO chips: {}", gpiod_detail::errno_text(err)));
  }
  std::vector<GpioChipInfo> chips;
  gpiod_chip* chip = nullptr;
  gpiod_foreach_chip(iter, chip) {
    chips.push_back(GpioChipInfo{gpiod_chip_name(chip), gpiod_chip_label(chip), gpiod_chip_num_lines(chip)});
  }
  gpiod_chip_iter_free(iter);
  return chips;
}

}  // namespace hubrt::hal
