// What a hubd that runs simulated boards adds to the composition root: the fake HAL backend (the
// board's device simulators, Modbus servers on loopback, virtual CAN) and the sim bridge stage
// (/sim/input, /sim/fault, /sim/<hub>/signals). A hub on a real board needs none of it, so the
// board build of hubd links no implementation (AssemblyRequest::simulation stays null) and the
// simulated station's hubd links hubrt_assembly_sim (fake_simulation.h). Chosen at link time by
// which program is built, never by #ifdef: boards stay data.
#pragma once

#include <memory>
#include <string>

#include <spdlog/logger.h>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/dds/participant.h"
#include "hubrt/hal/backend.h"
#include "hubrt/hal/board/board_config.h"
#include "hubrt/runtime/hub.h"

namespace hubrt::assembly {

class Simulation {
 public:
  // The backend of a simulated board: hal::Backend plus whatever the bridge stage needs of it.
  class SimulatedBackend {
   public:
    virtual ~SimulatedBackend() = default;
    [[nodiscard]] virtual hal::Backend& backend() noexcept = 0;
  };

  virtual ~Simulation() = default;
  // The fake backend of `board` (its simulation section), its simulators driven by `clock` (which
  // must outlive it). Errors: the simulators' (e.g. a Modbus server port in use).
  [[nodiscard]] virtual Expected<std::unique_ptr<SimulatedBackend>> open_backend(
      const hal::BoardConfig& board, const Clock& clock) const = 0;
  // The sim bridge's DDS entities for hub `hub_name` (readers of /sim/input, /sim/fault,
  // /sim/badge, the writer of /sim/<hub>/signals), without the backend: no device, and nothing is
  // published until the stage runs, so hubd opens them while its start-up twin check watches
  // discovery instead of after it. Errors: the DDS entity that could not be created.
  class PreparedBridge {
   public:
    virtual ~PreparedBridge() = default;
  };
  // `ros_namespace`: the hub's, in front of each of those topics (a station in a namespace).
  [[nodiscard]] virtual Expected<std::unique_ptr<PreparedBridge>> prepare_bridge(
      const dds::Participant& participant, const std::string& hub_name,
      const std::string& ros_namespace) const = 0;
  // The sim bridge stage over `prepared` (from prepare_bridge) and `backend` (from open_backend,
  // outliving the stage). Never fails.
  [[nodiscard]] virtual std::unique_ptr<runtime::CycleStage> bridge(
      std::unique_ptr<PreparedBridge> prepared, const hal::BoardConfig& board, SimulatedBackend& backend,
      std::shared_ptr<spdlog::logger> log) const = 0;
};

// The message of a program built without a simulation that is asked to run a simulated board.
inline constexpr std::string_view kNoSimulationHint =
    "this hubd is the board build, linked without the fake backend and the simulators: run "
    "simulated boards with the development build's hubd";

}  // namespace hubrt::assembly
