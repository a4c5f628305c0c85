// One row of docs/safety.md's time-to-safe table, written by the test that measured it: each test
// writes a small JSON file into the build tree (HUBRT_TIME_TO_SAFE_DIR, defined for the tests that
// record rows: one file per row, replaced by every run) and toolchain/time-to-safe-table renders
// the table from them (`make safety-table`). A row is never typed: a hazard this machine cannot
// produce is listed by the script as such, naming the test that covers its mechanism.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace hubrt::test_support {

struct TimeToSafe {
  std::string hazard;     // e.g. "SIGSTOP stall (4 s), then continued"
  std::string hub;        // hub type, e.g. "rsp_ecu"
  std::string outputs;    // what is made safe, e.g. "lock valve"
  std::string mechanism;  // what makes it safe
  double measured_s = 0;  // hazard (or its end) -> first State showing the node safe
  double bound_s = 0;     // what the measurement must not exceed
  std::string bound;      // how the bound is made up, e.g. "command timeout + one period"
  std::string test;       // the test that measured it
};

namespace detail {
inline std::string json_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c == '\n' ? ' ' : c;
  }
  return out + "\"";
}
}  // namespace detail

// Writes `row` as <HUBRT_TIME_TO_SAFE_DIR>/<file>.json. Without HUBRT_TIME_TO_SAFE_DIR nothing is
// written. Failures to write are ignored: the row is a by-product, the test's asserts are its own.
inline void record_time_to_safe([[maybe_unused]] const std::string& file,
                                [[maybe_unused]] const TimeToSafe& row) {
#ifdef HUBRT_TIME_TO_SAFE_DIR
  using detail::json_string;
  const std::filesystem::path dir(HUBRT_TIME_TO_SAFE_DIR);
  std::error_code ignored;
  std::filesystem::create_directories(dir, ignored);
  std::ofstream out(dir / (file + ".json"));
  out << "{\n  \"hazard\": " << json_string(row.hazard) << ",\n  \"hub\": " << json_string(row.hub)
      << ",\n  \"outputs\": " << json_string(row.outputs)
      << ",\n  \"mechanism\": " << json_string(row.mechanism) << ",\n  \"measured_s\": " << row.measured_s
      << ",\n  \"bound_s\": " << row.bound_s << ",\n  \"bound\": " << json_string(row.bound)
      << ",\n  \"test\": " << json_string(row.test) << "\n}\n";
#endif
}

}  // namespace hubrt::test_support
