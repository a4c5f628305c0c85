// errno → ErrorCode and text for libgpiod failures.
#pragma once

#include <string>

#include "hubrt/base/status.h"

namespace hubrt::hal::gpiod_detail {

// The system's text for an errno value ("Permission denied").
std::string errno_text(int err);

// ENODEV/ENXIO: the chip went away (unplugged, gpio-sim device disabled) → kUnavailable; else kIo.
Status line_io_status(int err) noexcept;

}  // namespace hubrt::hal::gpiod_detail
