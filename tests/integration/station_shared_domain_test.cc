// Two stations in one DDS domain, each under its own ROS namespace (design (a) of docs/plant.md):
// the same hub names twice on the domain, two station models, two planners. Each planner
// (hubctl play --namespace) must find its own station's hubs and drive its own station model
// (hubsim --namespace), so the use-case passes in both at once. A planner or a station model that
// reached the other station's hubs would move the other robot, take the other's tools or wait on
// the other's States, and a scenario would fail.
#include <future>

#include "station_scenario.h"

namespace hubrt::integration {
namespace {

StationOptions station_under(const std::string& ros_namespace) {
  StationOptions options = brisk_station(StationLayout::kNodeType);
  options.ros_namespace = ros_namespace;
  return options;
}

TEST(StationSharedDomain, TwoStationsInOneDomainEachPassTheUseCaseUnderTheirNamespace) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  auto cell_a = StationProcesses::start(*domain, station_under("/cell_a"));
  ASSERT_TRUE(cell_a) << cell_a.error().message;
  auto cell_b = StationProcesses::start(*domain, station_under("/cell_b"));
  ASSERT_TRUE(cell_b) << cell_b.error().message;
  const std::string scenario = std::string(HUBRT_SOURCE_DIR) + "/hubs/station/scenarios/use-case.yaml";
  // Generous, as expect_scenario_passes: only catches a hang (two stations under sanitizers).
  constexpr auto kPatience = std::chrono::seconds(200);
  auto played_b = std::async(std::launch::async, [&] { return cell_b->play(scenario, kPatience); });
  auto played_a = cell_a->play(scenario, kPatience);
  auto played = played_b.get();
  for (const auto* run : {&played_a, &played}) {
    ASSERT_TRUE(*run) << run->error().message << "\n" << cell_a->logs() << cell_b->logs();
    EXPECT_TRUE((*run)->status.exited_with(0)) << (*run)->status.describe() << "\n" << (*run)->output;
    EXPECT_NE((*run)->output.find("play: PASSED"), std::string::npos) << (*run)->output;
  }
  // The namespace is what picks the station: under one no station has, the planner's first step
  // (a command to the station model) finds no reader, although two station models are on the
  // domain. (Which hub a namespace picks: NodeLocatorTest.)
  test_support::Environment env = domain->env();
  env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
  auto stray = test_support::ChildProcess::start(
      HUBRT_HUBCTL_PATH, {"play", scenario, "--namespace", "/cell_c", "--timeout", "2"}, env);
  ASSERT_TRUE(stray) << stray.error().message;
  auto status = stray->wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(1)) << status->describe() << stray->stdout_text();
  EXPECT_NE(stray->stdout_text().find("nobody reads rt/cell_c/sim/station/command"), std::string::npos)
      << stray->stdout_text();
  // A namespace a hub file would refuse is refused here too, before anything is sent.
  auto refused =
      test_support::ChildProcess::start(HUBRT_HUBCTL_PATH, {"play", scenario, "--namespace", "/cell-a"}, env);
  ASSERT_TRUE(refused) << refused.error().message;
  auto refusal = refused->wait(kPatience);
  ASSERT_TRUE(refusal) << refusal.error().message;
  EXPECT_TRUE(refusal->exited_with(2)) << refusal->describe();
  EXPECT_NE(refused->stderr_text().find("'/cell-a' is not a valid ROS namespace"), std::string::npos)
      << refused->stderr_text();
}

}  // namespace
}  // namespace hubrt::integration
