#include "bench_common.h"

#include <signal.h>

#include <cstdlib>
#include <fstream>

#include <fmt/format.h>

namespace hubrt::bench {

Expected<test_support::TestDomain> join_private_domain() {
  auto domain = test_support::TestDomain::acquire();
  if (!domain) return domain;
  for (const auto& [name, value] : domain->env()) {
    setenv(name.c_str(), value.c_str(), 1);  // NOLINT(concurrency-mt-unsafe): before any thread
  }
  return domain;
}

namespace {
std::string& hubd_override() {
  static std::string path;
  return path;
}
}  // namespace

std::string hubd_path() {
  return hubd_override().empty() ? std::string(HUBRT_HUBD_PATH) : hubd_override();
}
void use_hubd(std::string path) {
  hubd_override() = std::move(path);
}
std::string hubctl_path() {
  return HUBRT_HUBCTL_PATH;
}
std::string source_dir() {
  return HUBRT_SOURCE_DIR;
}

Expected<test_support::ChildProcess> start_hubd(const std::vector<std::string>& args,
                                                const test_support::Environment& env) {
  std::vector<std::string> all = {"--board", "host-sim", "--log-level", "warn"};
  all.insert(all.end(), args.begin(), args.end());
  test_support::Environment full = env;
  full.emplace_back("HUBRT_CONFIG_DIR", source_dir());
  return test_support::ChildProcess::start(hubd_path(), all, full);
}

std::string board_hubd_path() {
  return HUBRT_HUBD_BOARD_PATH;
}

Expected<test_support::ChildProcess> start_board_hubd(const std::string& program,
                                                      const std::vector<std::string>& args) {
  std::vector<std::string> all = {"--board", "rpi4-dock-ecu", "--log-level", "warn"};
  all.insert(all.end(), args.begin(), args.end());
  return test_support::ChildProcess::start(program, all, {{"HUBRT_CONFIG_DIR", source_dir()}});
}

Expected<test_support::ChildProcess> start_raw_peer(const std::vector<std::string>& args) {
  auto child = test_support::ChildProcess::start(HUBRT_RAW_PEER_PATH, args);
  if (!child) return child;
  if (!child->wait_for_output("raw ", std::chrono::seconds(20))) {
    return make_error(ErrorCode::kTimeout, fmt::format("raw peer did not start: {}{}", child->stdout_text(),
                                                       child->stderr_text()));
  }
  return child;
}

void stop(test_support::ChildProcess& child) {
  if (child.signal(SIGTERM)) {
    if (!child.wait(std::chrono::seconds(5))) {
      (void)child.signal(SIGKILL);
      (void)child.wait(std::chrono::seconds(5));
    }
  }
}

hubctl::Summary summary_of(const std::vector<double>& values) {
  return hubctl::summarize(values);
}

nlohmann::ordered_json summary_json(const std::vector<double>& values) {
  const hubctl::Summary s = hubctl::summarize(values);
  nlohmann::ordered_json out;
  out["n"] = s.count;
  out["min"] = s.min;
  out["p50"] = s.p50;
  out["p90"] = s.p90;
  out["p99"] = s.p99;
  out["max"] = s.max;
  out["mean"] = s.mean;
  return out;
}

Expected<void> write_json(const std::string& path, const nlohmann::ordered_json& value) {
  std::ofstream out(path);
  out << value.dump(2) << "\n";
  if (!out) return make_error(ErrorCode::kIo, fmt::format("cannot write {}", path));
  return {};
}

void progress(const std::string& line) {
  fmt::print(stderr, "  {}\n", line);
}

}  // namespace hubrt::bench
