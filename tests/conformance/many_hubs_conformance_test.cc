// Scale (issue 16 point 6): 32 Dock ECU hubs on one host, each with its own name and ROS namespace,
// all conform under one `hubctl conformance --parallel` and none of them ends by itself. Labelled
// `slow` (32 sanitizer hubd processes take minutes on 2 cores): run with `ctest -L slow`. Before
// WriterWatch kept its loan buffers as large as its largest loan, hubs died with a corrupted heap
// as soon as the domain held more than 64 writers; `make bench` measures the same at 32 and 64
// hubs with the default thresholds (hubrt_bench_scale).
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/hub_process.h"
#include "hubrt/test_support/test_domain.h"

#include "failed_checks.h"

namespace hubrt::conformance_test {
namespace {

constexpr int kHubs = 32;
// Generous: 32 parallel sessions of ~10 s each in one sanitizer hubctl beside 32 sanitizer hubs.
constexpr auto kSuiteTimeout = std::chrono::seconds(600);

// The shipped Dock ECU configuration under its own name and namespace (commands address it alone).
std::string hub_file(const std::filesystem::path& dir, int index) {
  std::ifstream in(std::string(HUBRT_SOURCE_DIR) + "/hubs/dock_ecu/dock_ecu.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string name = fmt::format("dock_{:02}", index);
  const auto at = text.find("\nname: dock_ecu\n");
  EXPECT_NE(at, std::string::npos);
  if (at != std::string::npos) text.replace(at, 16, "\nname: " + name + "\n");
  text += fmt::format("namespace: /h{:02}\n", index);
  const auto path = dir / (name + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}

TEST(ManyHubsConformance, ThirtyTwoHubsOnOneHostAllConform) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  const auto dir = std::filesystem::temp_directory_path() / ("hubrt-many-hubs-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::vector<test_support::HubProcess> hubs;
  std::vector<std::string> args = {"conformance", "--json", "--parallel", "--thresholds", HUBRT_CI_THRESHOLDS,
                                   "--duration",  "2",      "--hold",     "0.6",          "--latency-samples",
                                   "20"};
  for (int i = 1; i <= kHubs; ++i) {
    test_support::HubProcessOptions options;
    options.hub = hub_file(dir, i);
    auto hub = test_support::HubProcess::start(*domain, options);
    ASSERT_TRUE(hub) << "hub " << i << ": " << hub.error().message;
    hubs.push_back(std::move(*hub));
    args.emplace_back("--hub");
    args.push_back(fmt::format("dock_{:02}", i));
  }
  test_support::Environment env = domain->env();
  env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
  auto child = test_support::ChildProcess::start(HUBRT_HUBCTL_PATH, args, env);
  ASSERT_TRUE(child) << child.error().message;
  auto status = child->wait(kSuiteTimeout);
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(status) << status.error().message;
  for (std::size_t i = 0; i < hubs.size(); ++i) {
    EXPECT_FALSE(hubs[i].process().wait(std::chrono::milliseconds(0)))
        << "hub " << i + 1 << " ended by itself:\n"
        << hubs[i].output();
  }
  const auto report = nlohmann::json::parse(child->stdout_text(), nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << child->stdout_text() << child->stderr_text();
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n"
                                      << child->stderr_text() << failed_checks(report);
  ASSERT_EQ(report["targets"].size(), static_cast<std::size_t>(kHubs)) << report.dump(2);
  std::set<std::string> passed;
  for (const auto& target : report["targets"]) {
    EXPECT_EQ(target["passed"], true) << target.dump(2) << failed_checks(target);
    if (target["passed"] == true) passed.insert(target["state_topic"].dump());
  }
  EXPECT_EQ(passed.size(), static_cast<std::size_t>(kHubs));
}

}  // namespace
}  // namespace hubrt::conformance_test
