#include "bench_common.h"

#include <signal.h>

#include <cstdlib>
#include <fstream>
#include <optional>

#include <fmt/format.h>

#include "hubrt/dds/domain.h"

namespace hubrt::bench {

Expected<test_support::TestDomain> join_private_domain() {
  // NOLINTBEGIN(concurrency-mt-unsafe): getenv and setenv before any thread
  const char* probed = std::getenv(kProbeDomainEnvVar);
  std::optional<std::uint32_t> probed_id;
  if (probed != nullptr) {
    char* end = nullptr;
    const unsigned long id = std::strtoul(probed, &end, 10);
    if (*probed == '\0' || *end != '\0' || id > dds::kMaxDomainId) {
      return make_error(
          ErrorCode::kInvalidArgument,
          fmt::format("{}={}: not a DDS domain id (0-{})", kProbeDomainEnvVar, probed, dds::kMaxDomainId));
    }
    probed_id = static_cast<std::uint32_t>(id);
  }
  auto domain = probed_id ? test_support::TestDomain::take(*probed_id) : test_support::TestDomain::acquire();
  if (!domain) return domain;
  for (const auto& [name, value] : domain->env()) setenv(name.c_str(), value.c_str(), 1);
  if (const char* xml = std::getenv(kProbeConfigEnvVar); probed_id && xml != nullptr) {
    setenv("CYCLONEDDS_URI", xml, 1);
  }
  // NOLINTEND(concurrency-mt-unsafe)
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
