// Runs a scenario of hubs/station/scenarios/ against a fresh simulated station and checks that
// every step passed; shared by the use-case and the fault tests.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "station_process.h"

namespace hubrt::integration {

// The station at a brisker pace than the real one, with the same behaviour: hubs at 20 Hz
// instead of 10 Hz (each wait for a State is shorter), quicker robot moves, the lift at its
// drive's top speed. Keeps the use-case run around 15 s on an idle machine.
inline StationOptions brisk_station(StationLayout layout) {
  StationOptions options;
  options.layout = layout;
  options.hubd_args = {"--rate", "20"};
  options.hubsim_args = {"--travel-ms", "150"};
  options.lift_speed_mm_s = 200;
  return options;
}

inline void expect_scenario_passes(const StationOptions& options, const std::string& scenario) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  auto station = StationProcesses::start(*domain, options);
  ASSERT_TRUE(station) << station.error().message;
  // Generous: every step has its own timeout in the scenario; this one only catches a hang, on a
  // loaded 2-core machine running sanitizer builds in parallel.
  const auto played = station->play(std::string(HUBRT_SOURCE_DIR) + "/hubs/station/scenarios/" + scenario,
                                    std::chrono::seconds(options.full ? 240 : 150));
  ASSERT_TRUE(played) << played.error().message << "\n" << station->logs();
  EXPECT_TRUE(played->status.exited_with(0)) << played->status.describe() << "\n"
                                             << played->output << "\n"
                                             << station->logs();
  EXPECT_NE(played->output.find("play: PASSED"), std::string::npos) << played->output;
  // For the record in the test log: what ran and how long it took.
  std::printf("%s", played->output.substr(played->output.rfind("play: ")).c_str());
}

inline void expect_scenario_passes(StationLayout layout, const std::string& scenario) {
  expect_scenario_passes(brisk_station(layout), scenario);
}

}  // namespace hubrt::integration
