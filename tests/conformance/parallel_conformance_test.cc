// `hubctl conformance --parallel`: several State topics tested at the same time, one thread each on
// one DDS participant. Two Dock ECUs that can be addressed apart — one in the node-type layout, one
// in the hub layout under its own name — so both sessions command and watch their own hub at once.
// Labelled "threaded" too, so that the ThreadSanitizer build runs hubctl's threads.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/hub_process.h"
#include "hubrt/test_support/test_domain.h"

#include "failed_checks.h"

namespace hubrt::conformance_test {
namespace {

// Generous: two sessions of ~10 s each, in sanitizer builds on a loaded machine.
constexpr auto kSuiteTimeout = std::chrono::seconds(150);

// The shipped Dock ECU configuration, in the hub layout and under another name.
std::string hub_layout_file(const std::filesystem::path& dir) {
  std::ifstream in(std::string(HUBRT_SOURCE_DIR) + "/hubs/dock_ecu/dock_ecu.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return at != std::string::npos;
  };
  EXPECT_TRUE(replace("layout: node_type", "layout: hub"));
  EXPECT_TRUE(replace("name: dock_ecu", "name: dock_hub"));
  const auto path = dir / "dock_hub.yaml";
  std::ofstream(path) << text;
  return path.string();
}

TEST(ParallelConformance, TwoHubsAtOnceBothConform) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  const auto dir =
      std::filesystem::temp_directory_path() / ("hubrt-parallel-conformance-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  test_support::HubProcessOptions node_layout;
  node_layout.hub = "dock_ecu";
  auto first = test_support::HubProcess::start(*domain, node_layout);
  ASSERT_TRUE(first) << first.error().message;
  test_support::HubProcessOptions hub_layout;
  hub_layout.hub = hub_layout_file(dir);
  auto second = test_support::HubProcess::start(*domain, hub_layout);
  ASSERT_TRUE(second) << second.error().message;

  test_support::Environment env = domain->env();
  env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
  auto child = test_support::ChildProcess::start(
      HUBRT_HUBCTL_PATH,
      {"conformance", "--json", "--parallel", "--hub", "dock_ecu", "--hub", "dock_hub", "--thresholds",
       HUBRT_CI_THRESHOLDS, "--duration", "2", "--hold", "0.6", "--latency-samples", "30"},
      env);
  ASSERT_TRUE(child) << child.error().message;
  auto status = child->wait(kSuiteTimeout);
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(status) << status.error().message;
  const auto report = nlohmann::json::parse(child->stdout_text(), nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << child->stdout_text() << child->stderr_text();
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n"
                                      << report.dump(2) << child->stderr_text() << failed_checks(report);
  ASSERT_EQ(report["targets"].size(), 2u) << report.dump(2);
  std::set<std::string> layouts;
  for (const auto& target : report["targets"]) {
    layouts.insert(target["layout"].get<std::string>());
    EXPECT_EQ(target["passed"], true) << target.dump(2) << failed_checks(target);
    EXPECT_GE(target["checks"].size(), 20u) << "every phase ran: " << target.dump(2);
  }
  EXPECT_EQ(layouts, (std::set<std::string>{"hub", "node_type"}));
}

}  // namespace
}  // namespace hubrt::conformance_test
