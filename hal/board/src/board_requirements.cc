#include "hubrt/hal/board/board_requirements.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace hubrt::hal {
namespace {

// What else a name is declared as on the board, e.g. "an output (line 12)"; empty when nothing.
std::string declared_as(const BoardConfig& board, std::string_view name) {
  if (const BoardInput* input = board.find_input(name))
    return fmt::format("an input (line {})", input->where.line);
  if (const BoardOutput* output = board.find_output(name)) {
    return fmt::format("an output (line {})", output->where.line);
  }
  if (const BoardCanBus* bus = board.find_can(name))
    return fmt::format("a CAN bus (line {})", bus->where.line);
  if (const BoardModbusDevice* device = board.find_modbus(name)) {
    return fmt::format("a Modbus device (line {})", device->where.line);
  }
  if (const BoardHttpDevice* device = board.find_http(name)) {
    return fmt::format("an HTTP device (line {})", device->where.line);
  }
  if (const BoardBadgeReader* reader = board.find_badge_reader(name)) {
    return fmt::format("an RFID reader (line {})", reader->where.line);
  }
  return {};
}

template <class Find>
Expected<void> check_kind(const BoardConfig& board, const BoardRequirements& required, std::string_view kind,
                          const std::vector<std::string>& names, Find find) {
  for (const std::string& name : names) {
    if (find(name)) continue;
    const std::string other = declared_as(board, name);
    if (other.empty()) {
      return make_error(ErrorCode::kFailedPrecondition,
                        fmt::format("hub {} needs {} '{}' but {} does not declare it", required.hub, kind,
                                    name, board.file));
    }
    return make_error(ErrorCode::kFailedPrecondition,
                      fmt::format("hub {} needs {} '{}' but {} declares it as {}", required.hub, kind, name,
                                  board.file, other));
  }
  return {};
}

}  // namespace

Expected<void> check_requirements(const BoardConfig& board, const BoardRequirements& required) {
  if (!board.wired_for(required.hub)) {
    return make_error(ErrorCode::kFailedPrecondition,
                      fmt::format("{} (board {}) is wired for hub {}, not {}", board.file, board.name,
                                  fmt::join(board.hubs, ", "), required.hub));
  }
  if (auto ok = check_kind(board, required, "input", required.inputs,
                           [&](const std::string& n) { return board.find_input(n) != nullptr; });
      !ok) {
    return ok;
  }
  if (auto ok = check_kind(board, required, "output", required.outputs,
                           [&](const std::string& n) { return board.find_output(n) != nullptr; });
      !ok) {
    return ok;
  }
  if (auto ok = check_kind(board, required, "CAN bus", required.can_buses,
                           [&](const std::string& n) { return board.find_can(n) != nullptr; });
      !ok) {
    return ok;
  }
  if (auto ok = check_kind(board, required, "Modbus device", required.modbus_devices,
                           [&](const std::string& n) { return board.find_modbus(n) != nullptr; });
      !ok) {
    return ok;
  }
  if (auto ok = check_kind(board, required, "HTTP device", required.http_devices,
                           [&](const std::string& n) { return board.find_http(n) != nullptr; });
      !ok) {
    return ok;
  }
  return check_kind(board, required, "RFID reader", required.badge_readers,
                    [&](const std::string& n) { return board.find_badge_reader(n) != nullptr; });
}

}  // namespace hubrt::hal
