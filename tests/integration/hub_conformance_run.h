// `hubctl conformance` against one hub type's hubd, for the conformance test each hub folder keeps
// (hubs/<hub>/test/*_conformance_test.cc; docs/new-hub.md step 9): the shipped hub file put in the
// layout under test, hubd on the hub's test board in the test's own DDS domain, the hub's profile
// (conformance.yaml) found through HUBRT_CONFIG_DIR, the CI thresholds.
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace hubrt::integration {

struct HubConformanceRun {
  std::string hub_dir;  // hubs/<hub>: <hub_name>.yaml is in it
  std::string hub_name;
  std::string board;   // the test board hubd runs on
  std::string layout;  // node_type | hub
  // Literal replacements in the hub file besides its layout (e.g. a relative path made absolute,
  // because the copy lives in a temporary folder); each must be found.
  std::vector<std::pair<std::string, std::string>> hub_file_edits;
  int state_topics = 1;  // how many State topics must conform
  std::string hubctl;
  std::string thresholds;
  // Generous: sanitizer builds on a loaded 2-core machine; one run takes about 8-17 s.
  std::chrono::seconds timeout{120};
};

// Runs it and records gtest failures (exit status, the PASS line, the safe-state check) with the
// report and hubd's output.
void expect_hub_conforms(const HubConformanceRun& run);

}  // namespace hubrt::integration
