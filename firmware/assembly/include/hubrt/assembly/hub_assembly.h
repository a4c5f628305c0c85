// Builds a runnable hub from its two files: the board (wiring) and the hub configuration
// (what runs on it), on the chosen HAL backend, joined to a DDS domain.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <spdlog/logger.h>

#include "hubrt/assembly/black_box_service.h"
#include "hubrt/assembly/simulation.h"
#include "hubrt/assembly/twin_watch.h"
#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/blackbox/black_box.h"
#include "hubrt/config/hub_config.h"
#include "hubrt/dds/domain.h"
#include "hubrt/dds/participant.h"
#include "hubrt/hal/backend.h"
#include "hubrt/hal/board/board_config.h"
#include "hubrt/hub_api/subscriptions.h"
#include "hubrt/runtime/cycle_runner.h"
#include "hubrt/runtime/hub.h"

namespace hubrt::assembly {

enum class BackendKind : std::uint8_t { kFake, kLinux };

struct AssemblyRequest {
  std::string board_file;
  std::string hub_file;
  // The two files as already loaded from board_file and hub_file, when the caller read them
  // (hubd does, to choose the backend and the security): not read again. Must outlive the call.
  const hal::BoardConfig* loaded_board = nullptr;
  const config::HubConfig* loaded_hub = nullptr;
  BackendKind backend = BackendKind::kFake;
  // What runs simulated boards (BackendKind::kFake): fake_simulation() of hubrt_assembly_sim in
  // the programs that link it; null in the board build of hubd, which then refuses the fake
  // backend (simulation.h).
  const Simulation* simulation = nullptr;
  dds::DomainConfig domain;
  std::optional<std::string> name;      // overrides the configured instance name
  std::optional<double> rate_hz;        // overrides the configured rate
  std::shared_ptr<spdlog::logger> log;  // defaults to spdlog's default logger
  runtime::Waker waker;
  // Log lines the process could not write (stderr closed), published in /diagnostics as
  // log_lines_dropped when set. Must outlive the assembled hub.
  const std::atomic<std::uint64_t>* log_lines_dropped = nullptr;
  // Guard against a twin (another hub publishing this hub's States, see twin_watch.h): nullopt
  // for none (tests, benchmarks); else the start-up discovery window (zero: no start-up check,
  // only the running watch) — a twin seen in it fails assembly with kBusy before any device is
  // opened.
  std::optional<Duration> twin_check;
  // The start-up check ends before the window once discovery has been quiet this long (and no
  // older hub without an identity is on the domain): StartupCheck in twin_rules.h.
  Duration twin_quiet = kDefaultTwinCheckQuiet;
  // Called from the cycle when this hub must stop because an earlier twin runs (thread-safe,
  // allocation-free, e.g. CycleRunner::request_stop).
  std::function<void()> request_stop;
  // The black box's directory when the hub file does not name one (hubd: $HUBRT_BLACKBOX_DIR or
  // /var/lib/hubrt/blackbox): with a value, a hub whose file leaves the black box enabled gets one
  // (AssembledHub::black_box); nullopt: no black box (most tests, benchmarks without it).
  std::optional<std::string> black_box_directory;
};

// What `hubd --check` validates: both files, loaded, with the overrides applied.
struct CheckedHub {
  hal::BoardConfig board;
  config::HubConfig config;
};

// Loads and checks both files and the overrides, finds the hub type and checks that the board
// provides every signal, bus and device the configured nodes need. Touches no device and no
// network (no backend, no DDS): what `hubd --check` runs. Errors name the file and line:
// kInvalidArgument / kNotFound / kFailedPrecondition, all configuration errors.
Expected<CheckedHub> check_hub(const AssemblyRequest& request);

// Destroyed in reverse order of the members: the hub (nodes, their devices and DDS endpoints)
// goes before the subscriptions, then the participant, then the backend.
struct AssembledHub {
  hal::BoardConfig board;
  config::HubConfig config;
  std::unique_ptr<Simulation::SimulatedBackend> simulated;  // owns the backend on a simulated board
  std::unique_ptr<hal::Backend> backend;                    // else the backend
  hal::Backend* devices = nullptr;                          // the backend in use, either way
  // Before the participant and the hub: the readers and writers that show it their samples go
  // first (black_box.h).
  std::unique_ptr<blackbox::BlackBox> black_box;
  std::optional<dds::Participant> participant;
  std::unique_ptr<TwinWatch> twin_watch;                  // when request.twin_check: uses the participant
  std::unique_ptr<hub_api::Subscriptions> subscriptions;  // its readers use the participant; the nodes use it
  std::unique_ptr<runtime::Hub> hub;
  const TwinStage* twins = nullptr;  // owned by the hub; says whether the hub yielded to a twin
  // Writes the black box on a fault and on request; last, so that its thread stops first.
  std::unique_ptr<BlackBoxService> black_box_service;
};

// check_hub(), then joins the domain, checks for a twin (request.twin_check), opens the backend and
// builds the nodes. Errors name the file and line, the device or the topic. `clock` drives the fake
// backend's simulators and must outlive the result.
Expected<std::unique_ptr<AssembledHub>> assemble_hub(const AssemblyRequest& request, const Clock& clock);

}  // namespace hubrt::assembly
