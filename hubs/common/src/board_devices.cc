#include "hubrt/hubs/board_devices.h"

#include <fmt/format.h>

namespace hubrt::hubs {

Expected<hal::SupervisedInput> open_board_input(const hal::BoardConfig& board, hal::Backend& backend,
                                                std::string_view owner, std::string_view signal, Time now) {
  const hal::BoardInput* input = board.find_input(signal);
  if (input == nullptr) {
    return make_error(ErrorCode::kNotFound,
                      fmt::format("{}: board {} has no input '{}'", owner, board.file, signal));
  }
  hal::SupervisedInput opened(backend, input->config);
  opened.open_now(now);
  return opened;
}

Expected<hal::SupervisedOutput> open_board_output(const hal::BoardConfig& board, hal::Backend& backend,
                                                  std::string_view owner, std::string_view signal, Time now) {
  const hal::BoardOutput* output = board.find_output(signal);
  if (output == nullptr) {
    return make_error(ErrorCode::kNotFound,
                      fmt::format("{}: board {} has no output '{}'", owner, board.file, signal));
  }
  // Pulled toward its safe level, so that the line falls safe when this process dies (the kernel
  // releases it) even before the unit's ExecStopPost (hubd --safe-outputs) runs.
  hal::DigitalOutputConfig config = output->config;
  config.bias_toward_safe = true;
  hal::SupervisedOutput opened(backend, config);
  opened.open_now(now);
  return opened;
}

}  // namespace hubrt::hubs
