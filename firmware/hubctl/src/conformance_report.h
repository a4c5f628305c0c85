// The conformance report: a table per State topic (one line per check: value, threshold,
// PASS/FAIL) for people, and the same as JSON for machines.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "conformance_checks.h"
#include "conformance_target.h"

namespace hubrt::hubctl {

struct TargetReport {
  Target target;
  std::vector<CheckResult> checks;
  [[nodiscard]] bool passed() const noexcept;
};

// Human report. `verbose`: the detail of every check, not only of failed ones.
std::string render_report(const std::vector<TargetReport>& reports, bool verbose);

// {"passed": bool, "targets": [{"state_topic", "hub", ..., "passed", "checks": [...]}]}.
nlohmann::ordered_json report_json(const std::vector<TargetReport>& reports);

}  // namespace hubrt::hubctl
