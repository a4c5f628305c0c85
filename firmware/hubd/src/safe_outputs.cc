#include "safe_outputs.h"

#include <algorithm>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hubrt/assembly/hub_types.h"
#include "hubrt/assembly/linux_device_libraries.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/board/board_requirements.h"
#include "hubrt/hal/linux/backend.h"

namespace hubrt::hubd {
namespace {

const char* level_name(bool active) {
  return active ? "active" : "inactive";
}

// Opens one output at its safe level, retrying while the line is busy.
Expected<std::unique_ptr<hal::DigitalOutput>> open_at_safe_level(hal::Backend& backend,
                                                                 const hal::DigitalOutputConfig& config,
                                                                 const BusyRetry& retry,
                                                                 const std::function<void(Duration)>& sleep) {
  for (int attempt = 1;; ++attempt) {
    auto output = backend.open_output(config);
    if (output || output.error().code != ErrorCode::kBusy || attempt >= retry.attempts) return output;
    sleep(retry.interval);
  }
}

// A board with nothing but its GPIO: the fake backend then starts no CAN or Modbus simulator
// (they would be this process's own, serving nobody).
hal::BoardConfig gpio_only(hal::BoardConfig board) {
  board.can.clear();
  board.modbus.clear();
  if (board.simulation) {
    board.simulation->can.clear();
    board.simulation->modbus.clear();
  }
  return board;
}

// Names the hub's buses, which --safe-outputs leaves alone, and why.
void log_untouched(const hal::BoardRequirements& required, spdlog::logger& log) {
  for (const std::string& bus : required.can_buses) {
    log.info("{} (CAN): not touched; the GPIO run lines are what enable the tool", bus);
  }
}

Expected<hal::BoardRequirements> hub_requirements(const hal::BoardConfig& board,
                                                  const config::HubConfig& hub) {
  const hub_api::HubType* type = assembly::find_hub_type(hub.type);
  if (type == nullptr) {
    return make_error(ErrorCode::kNotFound, fmt::format("{}: unknown hub type '{}'", hub.file, hub.type));
  }
  auto required = type->requirements(hub);
  if (!required) return required;
  if (auto ok = hal::check_requirements(board, *required); !ok) return std::move(ok).error();
  return required;
}

}  // namespace

void stop_devices(const config::HubConfig& hub, const hal::BoardConfig& board, hal::Backend* backend,
                  spdlog::logger& log) {
  const hub_api::HubType* type = assembly::find_hub_type(hub.type);
  if (type == nullptr) return;
  if (backend == nullptr) {
    for (const hal::BoardModbusDevice& device : board.modbus) {
      log.info("{} (Modbus): simulated inside the stopped hubd; nothing to stop", device.config.device);
    }
    return;
  }
  for (const hub_api::DeviceStopReport& stop : type->stop_devices(hub, board, *backend, kDeviceStopTimeout)) {
    if (stop.stopped) {
      log.info("{}: stopped ({})", stop.device, stop.message);
    } else {
      log.error("{}: NOT STOPPED, left to its own communication watchdog: {}", stop.device, stop.message);
    }
  }
}

Expected<std::vector<hal::DigitalOutputConfig>> safe_output_configs(const hal::BoardConfig& board,
                                                                    const config::HubConfig& hub) {
  auto required = hub_requirements(board, hub);
  if (!required) return std::move(required).error();
  std::vector<hal::DigitalOutputConfig> outputs;
  for (const hal::BoardOutput& output : board.outputs) {
    const auto& used = required->outputs;
    if (std::find(used.begin(), used.end(), output.config.signal) == used.end()) continue;
    hal::DigitalOutputConfig config = output.config;
    config.initial = config.safe;
    config.bias_toward_safe = true;
    outputs.push_back(std::move(config));
  }
  return outputs;
}

SafeOutputsReport drive_outputs_safe(hal::Backend& backend, std::span<const hal::DigitalOutputConfig> outputs,
                                     const BusyRetry& retry, const std::function<void(Duration)>& sleep,
                                     spdlog::logger& log) {
  SafeOutputsReport report;
  for (const hal::DigitalOutputConfig& config : outputs) {
    auto output = open_at_safe_level(backend, config, retry, sleep);
    Status written = output ? (*output)->write_safe() : Status(output.error().code);
    if (written.is_ok()) {
      log.info("{}: driven to its safe level ({})", config.signal, level_name(config.safe));
      report.driven.push_back(config.signal);
      continue;
    }
    std::string message = output ? fmt::format("{}: writing its safe level ({}) failed: {}", config.signal,
                                               level_name(config.safe), to_string(written.code()))
                                 : output.error().message;
    log.error("NOT SAFE: {}", message);
    report.failures.push_back(std::move(message));
  }
  return report;
}

int run_safe_outputs(const SafeOutputsRequest& request, spdlog::logger& log) {
  const auto config_error = [&log](const Error& error) {
    log.error("{}", error.message);
    return kSafeOutputsConfigError;
  };
  auto board = hal::load_board(request.board_file);
  if (!board) return config_error(board.error());
  auto hub = config::load_hub_config(request.hub_file);
  if (!hub) return config_error(hub.error());
  auto required = hub_requirements(*board, *hub);
  if (!required) return config_error(required.error());
  auto outputs = safe_output_configs(*board, *hub);
  if (!outputs) return config_error(outputs.error());

  SystemClock clock;  // the fake backend's simulators; outlives the backend
  std::unique_ptr<assembly::Simulation::SimulatedBackend> simulated;
  std::unique_ptr<hal::Backend> linux_backend;
  hal::Backend* backend = nullptr;
  if (request.backend == assembly::BackendKind::kFake) {
    if (request.simulation == nullptr) {
      return config_error(
          make_error(ErrorCode::kInvalidArgument, fmt::format("{}: the fake backend is not available: {}",
                                                              board->file, assembly::kNoSimulationHint)));
    }
    auto fake = request.simulation->open_backend(gpio_only(*board), clock);
    if (!fake) return config_error(fake.error());
    simulated = std::move(*fake);
    backend = &simulated->backend();
    log.warn("fake backend: the lines a stopped hubd drove lived in that process; these are fresh ones");
  } else {
    // The program's device libraries: a hub type's devices that must be told to stop (the lift
    // drive on Modbus) are opened as the hub opened them.
    linux_backend = std::make_unique<hal::LinuxBackend>(assembly::linux_device_libraries());
    backend = linux_backend.get();
  }

  log_untouched(*required, log);
  const auto sleep = [](Duration d) { std::this_thread::sleep_for(d); };
  const SafeOutputsReport report = drive_outputs_safe(*backend, *outputs, BusyRetry{}, sleep, log);
  stop_devices(*hub, *board, request.backend == assembly::BackendKind::kFake ? nullptr : backend, log);
  if (!report.failures.empty()) {
    std::vector<std::string> failed;
    for (const std::string& message : report.failures) failed.push_back(message.substr(0, message.find(':')));
    log.error("hub '{}' on board '{}': {} of {} outputs NOT driven safe: {}", hub->name, board->name,
              report.failures.size(), outputs->size(), fmt::join(failed, ", "));
    return kSafeOutputsFailed;
  }
  log.info("hub '{}' on board '{}': all {} outputs driven to their safe levels", hub->name, board->name,
           report.driven.size());
  return kSafeOutputsDone;
}

}  // namespace hubrt::hubd
