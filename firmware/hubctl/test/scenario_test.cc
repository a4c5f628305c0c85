// Scenario files: every step kind reads as documented, repeats expand, and mistakes are refused
// with file:line and the reason. The shipped scenarios load.
#include "scenario.h"

#include <filesystem>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace hubrt::hubctl {
namespace {

using std::chrono::milliseconds;
using ::testing::HasSubstr;

Expected<Scenario> parse(const std::string& text) {
  auto root = config::YamlMap::load_string(text, "play.yaml");
  if (!root) return std::move(root).error();
  return parse_scenario(*root);
}

TEST(Scenario, ReadsEveryKindOfStep) {
  auto scenario = parse(R"(description: all of them
rate_hz: 20
timeout: 3
steps:
  - command: {hub: tool_ecu, node: tool, action: tighten, run_id: 7, program: ladder_frame_bolt}
  - wait: {hub: tool_ecu, node: tool, until: "last_result.run_id == 7"}
  - wait: {station: true, until: ["robot_at == kit", "in_sync == true"], timeout: 0.5}
  - hold: {hub: rsp_ecu, node: rsp, while: "lock == closed", for: 1.5}
  - station: {action: move_robot, location: kit}
  - sim: {hub: rsp_ecu, signal: main_air, active: false}
  - fault: {hub: tool_ecu, device: tool_bus, fault: alarm, value: 4}
  - stop_sending: {hub: tool_ecu}
  - name: settle
    sleep: 0.25
  - badge: {hub: operator_hub, reader: operator_rfid, text: "0004123456"}
  - instruction: {step: bolts, text: "Place the bolts"}
)");
  ASSERT_TRUE(scenario) << scenario.error().message;
  EXPECT_EQ(scenario->description, "all of them");
  EXPECT_DOUBLE_EQ(scenario->rate_hz, 20.0);
  ASSERT_EQ(scenario->steps.size(), 11u);
  const auto& s = scenario->steps;
  EXPECT_EQ(s[0].kind, StepKind::kCommand);
  EXPECT_EQ(s[0].where, "play.yaml:5");
  EXPECT_EQ(s[0].target.hub, "tool_ecu");
  EXPECT_EQ(s[0].target.node, "tool");
  EXPECT_EQ(s[0].action, "tighten");
  ASSERT_EQ(s[0].fields.size(), 2u);
  EXPECT_EQ(s[0].fields[0].path, "run_id");
  EXPECT_EQ(s[0].fields[0].text, "7");
  EXPECT_EQ(s[0].describe(), "command tool_ecu/tool: tighten run_id=7 program=ladder_frame_bolt");
  EXPECT_EQ(s[1].kind, StepKind::kWait);
  EXPECT_EQ(s[1].timeout, std::chrono::seconds(3)) << "the scenario's default";
  EXPECT_EQ(s[2].target.station, true);
  EXPECT_EQ(s[2].conditions.size(), 2u);
  EXPECT_EQ(s[2].timeout, milliseconds(500));
  EXPECT_EQ(s[2].describe(), "wait station: robot_at == kit, in_sync == true");
  EXPECT_EQ(s[3].kind, StepKind::kHold);
  EXPECT_EQ(s[3].duration, milliseconds(1500));
  EXPECT_EQ(s[4].kind, StepKind::kStation);
  EXPECT_EQ(s[4].describe(), "station: move_robot location=kit");
  EXPECT_EQ(s[5].kind, StepKind::kSimInput);
  EXPECT_FALSE(s[5].active);
  EXPECT_EQ(s[6].kind, StepKind::kFault);
  EXPECT_EQ(s[6].value, 4u);
  EXPECT_EQ(s[7].kind, StepKind::kStopSending);
  EXPECT_EQ(s[7].target.node, "");
  EXPECT_EQ(s[8].kind, StepKind::kSleep);
  EXPECT_EQ(s[8].describe(), "settle");
  EXPECT_EQ(s[9].kind, StepKind::kBadge);
  EXPECT_EQ(s[9].target.hub, "operator_hub");
  EXPECT_EQ(s[9].signal, "operator_rfid");
  EXPECT_EQ(s[9].text, "0004123456");
  EXPECT_EQ(s[9].describe(), "badge operator_hub: a badge at operator_rfid")
      << "the badge stays out of reports";
  EXPECT_EQ(s[10].kind, StepKind::kInstruction);
  EXPECT_EQ(s[10].describe(), "instruction bolts: Place the bolts");
}

TEST(Scenario, RepeatsExpandWithTheirCount) {
  auto scenario = parse(R"(steps:
  - repeat:
      times: 3
      steps:
        - command: {hub: tool_ecu, node: tool, action: tighten, run_id: "${i}"}
        - wait: {hub: tool_ecu, node: tool, until: "last_result.run_id == ${i}"}
  - sleep: 0
)");
  ASSERT_TRUE(scenario) << scenario.error().message;
  ASSERT_EQ(scenario->steps.size(), 7u);
  EXPECT_EQ(scenario->steps[0].fields[0].text, "1");
  EXPECT_EQ(scenario->steps[3].conditions[0].text, "last_result.run_id == 2");
  EXPECT_EQ(scenario->steps[4].fields[0].text, "3");
  EXPECT_EQ(scenario->steps[4].where, "play.yaml:5") << "each copy points at the line it came from";
}

TEST(Scenario, MistakesNameFileLineAndWhatIsWrong) {
  const struct {
    std::string text;
    std::string expected;
  } cases[] = {
      {"steps:\n  - jump: {hub: a}\n", "play.yaml:2:11: steps[0].jump: unknown step 'jump'"},
      {"steps:\n  - sleep: 1\n    wait: {station: true, until: 'a == b'}\n", "a step is exactly one of"},
      {"steps:\n  - wait: {hub: a, node: b, until: 'x = 3'}\n", "unknown operator '='"},
      {"steps:\n  - wait: {hub: a, until: 'x == 3'}\n", "missing required key 'node'"},
      {"steps:\n  - wait: {hub: a, node: b, until: 'x == 3', timout: 3}\n", "timout"},
      {"steps:\n  - command: {hub: a, node: b}\n", "missing required key 'action'"},
      {"steps:\n  - command: {station: true, action: x}\n", "the world takes 'station:' steps"},
      {"steps:\n  - hold: {hub: a, node: b, while: 'x == 1'}\n", "missing required key 'for'"},
      {"steps:\n  - sim: {hub: a, signal: s, active: maybe}\n", "active"},
      {"steps:\n  - sleep: -1\n", "sleep"},
      {"steps:\n  - repeat: {times: 0, steps: [{sleep: 1}]}\n", "times"},
      {"steps: []\n", "no steps"},
      {"steps:\n  - sleep: 1\nspeed: 3\n", "speed"},
  };
  for (const auto& c : cases) {
    auto scenario = parse(c.text);
    ASSERT_FALSE(scenario) << c.text;
    EXPECT_THAT(scenario.error().message, HasSubstr(c.expected)) << c.text;
    EXPECT_THAT(scenario.error().message, HasSubstr("play.yaml:")) << c.text;
  }
}

TEST(Scenario, TheShippedScenariosLoad) {
  int loaded = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(std::string(HUBRT_SOURCE_DIR) +
                                                                         "/hubs/station/scenarios")) {
    if (entry.path().extension() != ".yaml") continue;
    auto scenario = load_scenario(entry.path().string());
    EXPECT_TRUE(scenario) << scenario.error().message;
    ++loaded;
  }
  EXPECT_GE(loaded, 5) << "the use-case and the fault scenarios";
}

}  // namespace
}  // namespace hubrt::hubctl
