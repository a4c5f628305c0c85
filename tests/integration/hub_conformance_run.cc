#include "hub_conformance_run.h"

#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/hub_process.h"
#include "hubrt/test_support/test_domain.h"

namespace hubrt::integration {
using test_support::HubProcess;
using test_support::HubProcessOptions;

void expect_hub_conforms(const HubConformanceRun& run) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  std::ifstream in(run.hub_dir + "/" + run.hub_name + ".yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::pair<std::string, std::string>> edits = run.hub_file_edits;
  edits.emplace_back("layout: node_type", "layout: " + run.layout);
  for (const auto& [from, to] : edits) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << run.hub_name << ".yaml has no '" << from << "'";
    text.replace(at, from.size(), to);
  }
  const auto hub_file =
      std::filesystem::path(::testing::TempDir()) / (run.hub_name + "-" + run.layout + ".yaml");
  std::ofstream(hub_file) << text;

  HubProcessOptions options;
  options.board = run.board;
  options.hub = hub_file.string();
  auto hub = HubProcess::start(*domain, options);
  ASSERT_TRUE(hub) << hub.error().message;

  test_support::Environment env = domain->env();
  env.emplace_back("HUBRT_CONFIG_DIR", test_support::config_dir());
  auto suite =
      test_support::ChildProcess::start(run.hubctl,
                                        {"conformance", "--hub", run.hub_name, "--thresholds", run.thresholds,
                                         "--duration", "2", "--hold", "0.6", "--latency-samples", "30"},
                                        env);
  ASSERT_TRUE(suite) << suite.error().message;
  auto status = suite->wait(run.timeout);
  ASSERT_TRUE(status) << status.error().message << "\n" << suite->stderr_text();
  const std::string report = suite->stdout_text() + suite->stderr_text();
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << report << "\n" << hub->output();
  const std::string topics = std::to_string(run.state_topics) + " of " + std::to_string(run.state_topics);
  EXPECT_NE(report.find("PASS: " + topics + " State topic(s) conform"), std::string::npos) << report;
  // The profile's safe state was checked, not skipped.
  EXPECT_NE(report.find("safe-state fields"), std::string::npos) << report;
}

}  // namespace hubrt::integration
