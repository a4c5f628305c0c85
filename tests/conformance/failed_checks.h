// The failed checks of a `hubctl conformance --json` report, one line each. A failure message
// prints them after the whole report: CI shows a failed test's last lines only, and the report of
// a hub is longer than that, so the check that failed would otherwise be cut away.
#pragma once

#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace hubrt::conformance_test {

// `report` is a whole report (its "targets") or one target.
inline std::string failed_checks(const nlohmann::json& report) {
  std::string out;
  const auto add_target = [&](const nlohmann::json& target) {
    if (!target.contains("checks")) return;
    for (const auto& check : target["checks"]) {
      if (check.value("verdict", "") != "FAIL") continue;
      out += fmt::format("FAILED {} {}: {} {} (threshold {}) {}\n", target.value("hub", "?"),
                         target.value("state_topic", "?"), check.value("check", "?"), check.value("text", ""),
                         check.value("threshold", ""), check.value("detail", ""));
    }
  };
  if (report.contains("targets")) {
    for (const auto& target : report["targets"]) add_target(target);
  } else {
    add_target(report);
  }
  return out.empty() ? std::string("no check failed\n") : out;
}

}  // namespace hubrt::conformance_test
