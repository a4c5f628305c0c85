// What each step of a `hubctl play` scenario does: commands handed to the planner's loop, waits
// and holds judged on the States that arrive, station commands, simulated inputs and faults sent
// once. Over the DDS side in scenario_traffic.h; the run and its report are scenario_runner.h's.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenario.h"
#include "scenario_traffic.h"

namespace hubrt::hubctl {

struct StepResult {
  bool ok = true;
  std::string detail;  // why it failed, several lines
};

inline StepResult failed(std::string detail) {
  return StepResult{false, std::move(detail)};
}

// `text` with `pad` before every line.
std::string indent(const std::string& text, std::string_view pad);

// Not thread-safe; one run at a time.
class StepExecutor {
 public:
  // `traffic` must outlive this.
  explicit StepExecutor(ScenarioTraffic& traffic) : traffic_(traffic) {}

  // Runs `step` to its end (a wait until its conditions hold, its timeout or Ctrl-C).
  StepResult execute(const Step& step);

 private:
  StepResult command(const Step& step);
  StepResult stop_sending(const Step& step);
  StepResult wait(const Step& step);
  StepResult hold(const Step& step);
  StepResult station(const Step& step);
  StepResult sim_input(const Step& step);
  StepResult badge(const Step& step);
  StepResult instruction(const Step& step);
  StepResult fault(const Step& step);
  StepResult to_hub(const std::string& topic, const std::string& hub, const msgs::TypeInfo& type,
                    const nlohmann::ordered_json& document);

  ScenarioTraffic& traffic_;
  bool looked_for_screens_ = false;  // the first instruction waited for discovery to find screens
  // Each instruction a new number, also across runs of hubctl (a screen takes a repeated number
  // for the same instruction): counted on from the time this hubctl started.
  std::uint32_t instruction_seq_ = static_cast<std::uint32_t>(
      std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch())
          .count());
};

}  // namespace hubrt::hubctl
