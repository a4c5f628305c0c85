// What the benchmark programs share: a private DDS domain on loopback, starting hubd and the raw
// baselines as processes, percentiles as JSON, and writing results.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hubrt/base/status.h"
#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/test_domain.h"

#include "stats.h"

namespace hubrt::bench {

// Takes a private domain id (TestDomain) and puts it and the loopback configuration into this
// process's environment, for the raw C API participants created here and for every child.
// As a probe of a plant (bench/plant.py): with HUBRT_BENCH_DOMAIN set, that domain instead (where
// the plant's stations run), and HUBRT_BENCH_CYCLONEDDS_URI, when set, the plant's Cyclone
// configuration instead of the loopback one. Errors: no free domain id; HUBRT_BENCH_DOMAIN not an
// id or held by another benchmark.
inline constexpr const char* kProbeDomainEnvVar = "HUBRT_BENCH_DOMAIN";
inline constexpr const char* kProbeConfigEnvVar = "HUBRT_BENCH_CYCLONEDDS_URI";
Expected<test_support::TestDomain> join_private_domain();

// Starts hubd (this build's) with `args` after `--board host-sim --log-level warn`; returns at
// once (the benchmarks wait for its first State on the wire). Errors: spawning failed.
Expected<test_support::ChildProcess> start_hubd(const std::vector<std::string>& args,
                                                const test_support::Environment& env = {});
// The Dock ECU's board program of hubd (board/dock_ecu/hubd, what its package installs: the Dock
// ECU's hub type alone, no fake backend, no simulators) with `args` after `--board rpi4-dock-ecu --log-level
// warn`: the Dock ECU on the Linux backend. On a machine without the Pi's GPIO chip its devices are missing
// (supervised, opened again with back-off; its outputs drive nothing) and it publishes its State as on a Pi.
// `program`: that board program of this build (board_hubd_path()) or of another build, e.g. the
// host-board preset's, built with the packages' size flags (bench/run). Errors: spawning.
Expected<test_support::ChildProcess> start_board_hubd(const std::string& program,
                                                      const std::vector<std::string>& args);
std::string board_hubd_path();
// hubrt_bench_raw_peer with `args`; waits for its ready line.
Expected<test_support::ChildProcess> start_raw_peer(const std::vector<std::string>& args);
// SIGTERM and reap (SIGKILL after 5 s).
void stop(test_support::ChildProcess& child);

std::string hubd_path();
// Makes start_hubd() run `path` instead of this build's hubd (e.g. another build, to compare).
void use_hubd(std::string path);
std::string hubctl_path();
std::string source_dir();

// {"n", "min", "p50", "p90", "p99", "max", "mean"} of `values` (already in the unit wanted).
nlohmann::ordered_json summary_json(const std::vector<double>& values);
hubctl::Summary summary_of(const std::vector<double>& values);

// Writes `value` to `path` (pretty), or fails with the file named.
Expected<void> write_json(const std::string& path, const nlohmann::ordered_json& value);

// One progress line on stderr, so that a long run shows where it is.
void progress(const std::string& line);

}  // namespace hubrt::bench
