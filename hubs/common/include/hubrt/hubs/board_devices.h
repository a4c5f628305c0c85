// What every hub type does to hand its nodes their devices: find a signal on the board and open
// it as a supervised device (hubrt/hal/common/supervised_device.h) through the backend.
#pragma once

#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/backend.h"
#include "hubrt/hal/board/board_config.h"
#include "hubrt/hal/common/supervised_device.h"

namespace hubrt::hubs {

// Opens the board's input / output `signal` now (an output pulled toward its safe level:
// DigitalOutputConfig::bias_toward_safe). A device that fails to open is no error here: it
// is returned not open, its reason in error(), and retried with back-off by its user. Allocates.
// Errors: kNotFound when the board has no such signal: "<owner>: board <file> has no input '<signal>'".
// `backend` must outlive the device.
Expected<hal::SupervisedInput> open_board_input(const hal::BoardConfig& board, hal::Backend& backend,
                                                std::string_view owner, std::string_view signal, Time now);
Expected<hal::SupervisedOutput> open_board_output(const hal::BoardConfig& board, hal::Backend& backend,
                                                  std::string_view owner, std::string_view signal, Time now);

}  // namespace hubrt::hubs
