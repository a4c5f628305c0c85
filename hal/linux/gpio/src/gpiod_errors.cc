#include "gpiod_errors.h"

#include <cerrno>
#include <system_error>

namespace hubrt::hal::gpiod_detail {

std::string errno_text(int err) {
  return std::generic_category().message(err);
}

Status line_io_status(int err) noexcept {
  if (err == ENODEV || err == ENXIO) return Status(ErrorCode::kUnavailable);
  return Status(ErrorCode::kIo);
}

}  // namespace hubrt::hal::gpiod_detail
