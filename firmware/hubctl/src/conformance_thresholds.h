// The bounds `hubctl conformance` judges a hub by. Every bound has a documented default and the
// reason for it in one table (conformance_thresholds.cc), which --print-thresholds shows and
// docs/conformance.md repeats; a YAML file (--thresholds) and --set KEY=VALUE override them.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "hubrt/base/status.h"

namespace hubrt::hubctl {

struct Thresholds {
  double first_state_ms = 0;  // start (or discovery) -> first State
  double rate_error_pct = 0;  // |measured - expected| / expected
  double jitter_p50_pct = 0;  // |period - nominal|, as a share of the nominal period
  double jitter_p99_pct = 0;
  double jitter_max_pct = 0;
  double jitter_floor_ms = 0;  // every jitter bound is at least this
  double seq_gaps = 0;         // missing or repeated sequence numbers
  double extra_states = 0;     // States beyond the heartbeat while one command repeats
  double echo_p50_ms = 0;      // command written -> State with that echo received
  double echo_p99_ms = 0;
  double t_plus_tolerance_ms = 0;  // t_plus vs the receiver's clock; t_plus right after a change
  double watchdog_slack_ms = 0;    // beyond command timeout + one period
};

// One row of the table: the key used in files and --set, the default, its unit and why.
struct ThresholdSpec {
  std::string_view key;
  double Thresholds::*field;
  double default_value;
  std::string_view unit;
  std::string_view reason;
};

// Every threshold, in report order. Thread-safe (constant data).
std::span<const ThresholdSpec> threshold_specs() noexcept;

// The documented defaults.
Thresholds default_thresholds() noexcept;

// Applies a YAML file of `key: value` pairs (keys from threshold_specs()) on top of `thresholds`.
// Errors name file:line:col and the key: unknown key (with the known ones), not a number, negative.
Expected<void> load_thresholds_file(const std::string& path, Thresholds& thresholds);

// Applies one `key=value` (from --set). Errors: kInvalidArgument naming the key or value.
Expected<void> apply_threshold_assignment(std::string_view assignment, Thresholds& thresholds);

// The table as text: key, value in force, unit, default and reason; for --print-thresholds.
std::string describe_thresholds(const Thresholds& in_force);

}  // namespace hubrt::hubctl
