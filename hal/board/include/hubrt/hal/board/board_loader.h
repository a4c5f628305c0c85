// Loads and validates a board file (schema: boards/README.md).
#pragma once

#include <string>

#include "hubrt/base/status.h"
#include "hubrt/hal/board/board_config.h"

namespace hubrt::hal {

// Reads `path` and validates it. Errors name file:line:col, the key path and what is wrong:
// unknown keys, bad values, missing sections, an unknown chip, a line used twice (naming both
// uses), a signal declared as both input and output, simulators wired to signals that do not
// exist or that another simulator already drives. kNotFound when the file does not exist,
// kInvalidArgument for everything else. Thread-safe (no shared state).
Expected<BoardConfig> load_board(const std::string& path);

// The same for text in memory; `name` stands in for the file name in messages.
Expected<BoardConfig> load_board_string(const std::string& text, const std::string& name);

}  // namespace hubrt::hal
