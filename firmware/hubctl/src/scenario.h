// A scenario for `hubctl play`: a YAML file with a list of steps the way the planner and the
// world would act on a station. The format (hubs/station/README.md has examples):
//
//   description: what it shows            # optional
//   rate_hz: 10                           # how often commands are repeated (default 10)
//   timeout: 10                           # default seconds a wait may take (default 10)
//   steps:
//     - command: {hub: rsp_ecu, node: rsp, action: lock, gripper: keep}   # other keys: fields
//     - wait: {hub: rsp_ecu, node: rsp, until: "locked == true", timeout: 5}
//     - wait: {station: true, until: ["robot_at == kit", "in_sync == true"]}
//     - hold: {hub: rsp_ecu, node: rsp, while: "lock == closed", for: 1.0}
//     - station: {action: move_robot, location: kit}       # other keys: StationCommand fields
//     - sim: {hub: rsp_ecu, signal: main_air, active: false}
//     - badge: {hub: operator_hub, reader: operator_rfid, text: "0004123456"}   # /sim/badge
//     - instruction: {step: bolts, text: "Place the 24 bolts"}   # /operator/instruction, the screen
//     - fault: {hub: tool_ecu, device: tool_bus, fault: power_off}        # value: optional
//     - stop_sending: {hub: tool_ecu}                      # or {hub, node}
//     - sleep: 0.5
//     - repeat: {times: 12, steps: [...]}                  # ${i} in any text = 1..times
//     - include: common/at-rest.yaml                       # its steps, path relative to this file
//
// Every step may carry `name:`, shown in the report instead of the generated description.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/config/yaml_map.h"

#include "predicate.h"

namespace hubrt::hubctl {

enum class StepKind : std::uint8_t {
  kCommand,
  kWait,
  kHold,
  kStation,
  kSimInput,
  kBadge,
  kInstruction,
  kFault,
  kStopSending,
  kSleep
};

// Whose State or command: a node of a hub, or the station model's world.
struct StepTarget {
  std::string hub;
  std::string node;      // empty for stop_sending of a whole hub
  bool station = false;  // the station model (hubsim)
};

struct FieldText {
  std::string path;  // as set_field takes it, e.g. "run_id"
  std::string text;
};

struct Step {
  StepKind kind = StepKind::kSleep;
  std::string where;  // "file:line"
  std::string name;   // from `name:`, else empty
  StepTarget target;
  std::string action;                 // command, station
  std::vector<FieldText> fields;      // command, station: the other keys
  std::vector<Predicate> conditions;  // wait (until), hold (while): all must hold
  Duration timeout{};                 // wait
  Duration duration{};                // hold (for), sleep
  std::string signal;                 // sim; badge: the reader; instruction: the step's name
  std::string text;                   // badge: what the reader sends; instruction: what to do
  bool active = false;                // sim
  std::string device, fault;          // fault
  std::uint32_t value = 0;            // fault

  // One line: "wait rsp_ecu/rsp: lock == closed" (or the step's name).
  [[nodiscard]] std::string describe() const;
};

struct Scenario {
  std::string file;
  std::string description;
  double rate_hz = 10.0;
  Duration default_timeout = std::chrono::seconds(10);
  std::vector<Step> steps;  // repeats expanded
};

// Loads and checks a scenario. Errors name file:line:col, the key and the problem (unknown step
// kind or key, a condition that does not parse, a missing target, bad numbers). Not thread-safe.
Expected<Scenario> load_scenario(const std::string& path);
Expected<Scenario> parse_scenario(const config::YamlMap& root);

}  // namespace hubrt::hubctl
