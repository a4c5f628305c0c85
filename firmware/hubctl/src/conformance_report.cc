#include "conformance_report.h"

#include <algorithm>

#include <fmt/format.h>

namespace hubrt::hubctl {
namespace {

std::string describe(const Target& t) {
  std::string where = t.layout == TargetLayout::kNodeType
                          ? fmt::format("hub {} ({}), node {} of type {}", t.hub_name,
                                        t.hub_type.empty() ? "type unknown" : t.hub_type, t.node_name,
                                        t.node_type.empty() ? "unknown" : t.node_type)
                          : fmt::format("hub {} ({}), hub layout", t.hub_name,
                                        t.hub_type.empty() ? "type unknown" : t.hub_type);
  const std::string rate =
      t.period_s > 0 ? fmt::format("{:.3f} Hz (from {})", 1.0 / t.period_s, t.period_source) : "rate unknown";
  const std::string timeout = t.timeout_s > 0 ? fmt::format("command timeout {:.0f} ms (from {})",
                                                            t.timeout_s * 1e3, t.timeout_source)
                                              : "command timeout unknown";
  const std::string commands =
      t.command_topic.empty() ? "" : fmt::format(", commands on {}", t.command_topic);
  return fmt::format("{}\n  expected {}, {}{}", where, rate, timeout, commands);
}

}  // namespace

bool TargetReport::passed() const noexcept {
  return !checks.empty() && std::none_of(checks.begin(), checks.end(),
                                         [](const CheckResult& c) { return c.verdict == Verdict::kFail; });
}

std::string render_report(const std::vector<TargetReport>& reports, bool verbose) {
  std::string out;
  std::size_t conforming = 0;
  for (const TargetReport& report : reports) {
    out += fmt::format("{} — {}\n", report.target.state_topic, describe(report.target));
    out += fmt::format("  {:<40} {:>16}  {:<18} {}\n", "CHECK", "VALUE", "THRESHOLD", "RESULT");
    std::size_t failures = 0;
    for (const CheckResult& c : report.checks) {
      out += fmt::format("  {:<40} {:>16}  {:<18} {}\n", c.title, c.value, c.threshold, to_string(c.verdict));
      if (c.verdict == Verdict::kFail) ++failures;
      if (!c.detail.empty() && (verbose || c.verdict == Verdict::kFail))
        out += fmt::format("      {}\n", c.detail);
    }
    if (report.passed()) {
      ++conforming;
      out += fmt::format("  => PASS ({} checks)\n\n", report.checks.size());
    } else {
      out += fmt::format("  => FAIL ({} of {} checks failed)\n\n", failures, report.checks.size());
    }
  }
  out += fmt::format("{}: {} of {} State topic(s) conform\n", conforming == reports.size() ? "PASS" : "FAIL",
                     conforming, reports.size());
  return out;
}

nlohmann::ordered_json report_json(const std::vector<TargetReport>& reports) {
  nlohmann::ordered_json targets = nlohmann::ordered_json::array();
  bool all = !reports.empty();
  for (const TargetReport& report : reports) {
    const Target& t = report.target;
    nlohmann::ordered_json checks = nlohmann::ordered_json::array();
    for (const CheckResult& c : report.checks) {
      nlohmann::ordered_json check;
      check["check"] = c.id;
      check["title"] = c.title;
      check["verdict"] = std::string(to_string(c.verdict));
      check["value"] = c.number ? nlohmann::ordered_json(*c.number) : nlohmann::ordered_json(nullptr);
      check["limit"] = c.limit ? nlohmann::ordered_json(*c.limit) : nlohmann::ordered_json(nullptr);
      check["unit"] = c.unit;
      check["text"] = c.value;
      check["threshold"] = c.threshold;
      check["detail"] = c.detail;
      checks.push_back(std::move(check));
    }
    nlohmann::ordered_json entry;
    entry["state_topic"] = t.state_topic;
    entry["hub"] = t.hub_name;
    entry["hub_type"] = t.hub_type;
    entry["layout"] = t.layout == TargetLayout::kNodeType ? "node_type" : "hub";
    entry["node"] = t.node_name;
    entry["node_type"] = t.node_type;
    entry["command_topic"] = t.command_topic;
    entry["rate_hz"] =
        t.period_s > 0 ? nlohmann::ordered_json(1.0 / t.period_s) : nlohmann::ordered_json(nullptr);
    entry["rate_source"] = t.period_source;
    entry["command_timeout_ms"] =
        t.timeout_s > 0 ? nlohmann::ordered_json(t.timeout_s * 1e3) : nlohmann::ordered_json(nullptr);
    entry["command_timeout_source"] = t.timeout_source;
    entry["passed"] = report.passed();
    entry["checks"] = std::move(checks);
    all = all && report.passed();
    targets.push_back(std::move(entry));
  }
  nlohmann::ordered_json root;
  root["passed"] = all;
  root["targets"] = std::move(targets);
  return root;
}

}  // namespace hubrt::hubctl
