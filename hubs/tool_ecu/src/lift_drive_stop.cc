#include "lift_drive_stop.h"

#include <algorithm>

#include <fmt/format.h>

#include "hubrt/hal/common/threaded_async_modbus.h"
#include "hubrt/protocol/lift_drive_modbus.h"

namespace hubrt::tool_ecu {

hub_api::DeviceStopReport stop_lift_drive(const LiftSettings& settings, const hal::BoardConfig& board,
                                          hal::Backend& backend, Duration timeout) {
  namespace ld = protocol::lift_drive;
  hub_api::DeviceStopReport report{settings.device, false, {}};
  const hal::BoardModbusDevice* device = board.find_modbus(settings.device);
  if (device == nullptr) {
    report.message = fmt::format("board {} has no Modbus device '{}'", board.file, settings.device);
    return report;
  }
  hal::ModbusConfig config = device->config;
  config.response_timeout = std::min(config.response_timeout, timeout);
  const std::string where = hal::describe_modbus(config);
  auto client = backend.open_modbus(config);
  if (!client) {
    report.message = fmt::format("{}: not stopped: {}", where, client.error().message);
    return report;
  }
  const Status written = (*client)->write_register(ld::holding::kControlWord, 0);
  if (!written.is_ok()) {
    report.message =
        fmt::format("{}: not stopped: writing control word 0 failed: {}", where, to_string(written.code()));
    return report;
  }
  report.stopped = true;
  report.message =
      fmt::format("{}: control word 0 written: power stage off, the lift held on its brake", where);
  return report;
}

}  // namespace hubrt::tool_ecu
