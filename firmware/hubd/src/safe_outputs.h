// `hubd --board B --hub H --safe-outputs`: drives every GPIO output the hub uses on the board to
// its configured safe level, then exits. The board package's unit runs it as ExecStopPost=, so
// the outputs are made safe after any end of hubd, including those no handler sees (SIGKILL, the
// OOM killer, a crash): see docs/deploy.md, "Safe outputs after any stop".
//
// It joins no DDS domain and opens nothing but those outputs and the devices the hub type says
// must be told to stop (HubType::stop_devices: the Tool ECU's lift drive, one Modbus write with a
// short timeout, best effort and logged; the drive's own communication watchdog, which the hub
// wrote on every exchange, stops it anyway within drive_watchdog_ms of the hub's last request —
// docs/protocols/lift-drive-modbus.md). No inputs, no CAN bus: each CAN bus is named in the log as
// not touched.
#pragma once

#include <functional>
#include <span>
#include <string>
#include <vector>

#include <spdlog/logger.h>

#include "hubrt/assembly/hub_assembly.h"
#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/config/hub_config.h"
#include "hubrt/hal/backend.h"
#include "hubrt/hal/board/board_config.h"

namespace hubrt::hubd {

// Exit codes of --safe-outputs, as hubd's: every output driven safe; at least one output could
// not be (each one named in the log); the board or hub file is broken, or the board is not wired
// for the hub.
inline constexpr int kSafeOutputsDone = 0;
inline constexpr int kSafeOutputsFailed = 1;
inline constexpr int kSafeOutputsConfigError = 2;

// A line still held by a hubd that was just killed is released by the kernel when that process's
// files are closed, which can trail the kill by a moment (a big address space to tear down first;
// systemd runs ExecStopPost only after the main process is gone, a shell after `kill -9` may not
// wait). So a busy line is tried again, `attempts` times in all, `interval` apart: 40 × 50 ms =
// 2 s. A line still busy then is held by a live program, which --safe-outputs must not fight.
struct BusyRetry {
  int attempts = 40;
  Duration interval = std::chrono::milliseconds(50);
};

// The outputs `board` wires for the hub `hub` is a configuration of, in board order, each with
// `initial` set to its safe level (opening it then drives nothing else) and `bias_toward_safe`.
// Errors (kNotFound, kInvalidArgument, kFailedPrecondition): unknown hub type, bad node settings,
// a board not wired for the hub or lacking a signal; messages name the file.
Expected<std::vector<hal::DigitalOutputConfig>> safe_output_configs(const hal::BoardConfig& board,
                                                                    const config::HubConfig& hub);

struct SafeOutputsReport {
  std::vector<std::string> driven;    // signals driven to their safe level
  std::vector<std::string> failures;  // one message per output that was not, naming it
};

// Opens each of `outputs` on `backend` and writes its safe level; a kBusy open is retried as
// `retry` says, sleeping with `sleep`. Every output is tried, whatever happened to the others.
// Logs one line per output to `log`. Thread-safety: as the backend's open_output.
SafeOutputsReport drive_outputs_safe(hal::Backend& backend, std::span<const hal::DigitalOutputConfig> outputs,
                                     const BusyRetry& retry, const std::function<void(Duration)>& sleep,
                                     spdlog::logger& log);

// How long the stop of one device may take (a drive answers within 10 ms; a connection attempt to
// one that is gone is bounded by this too): the unit's ExecStopPost must end promptly.
inline constexpr Duration kDeviceStopTimeout = std::chrono::milliseconds(200);

// Tells the hub type's devices to stop (HubType::stop_devices), logging each: "stopped", or
// "NOT STOPPED" with the reason. `backend` null (the fake backend, whose simulated devices lived
// in the stopped hubd): each Modbus device is named as having nothing to stop. A failed stop does
// not change --safe-outputs' exit status: it is best effort, the device's own watchdog the bound.
void stop_devices(const config::HubConfig& hub, const hal::BoardConfig& board, hal::Backend* backend,
                  spdlog::logger& log);

struct SafeOutputsRequest {
  std::string board_file;  // found by hubd as for a run
  std::string hub_file;
  assembly::BackendKind backend = assembly::BackendKind::kLinux;  // chosen as for a run
  // For the fake backend (simulated boards); null in the board build, which refuses it.
  const assembly::Simulation* simulation = nullptr;
};

// The whole of `hubd --safe-outputs`: loads the files, opens the backend (the fake backend with
// the board's GPIO simulators only: no CAN network, no Modbus server), drives the outputs and
// returns one of the exit codes above. Logs what it did and what failed to `log`.
int run_safe_outputs(const SafeOutputsRequest& request, spdlog::logger& log);

}  // namespace hubrt::hubd
