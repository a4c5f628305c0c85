// Many hubs on one host: for each size (1, 8, 32 by default) start that many Dock ECU hubs, each
// with its own name and ROS namespace (so that commands address one hub alone), and measure
//   discovery   spawn of the first hub -> a waiting subscriber matched every hub's State writer
//   all heard   ... -> that subscriber received a State from every hub
//   CPU, RSS    of all hubs together over a window, and per hub
//   conforming  `hubctl conformance --parallel` against all of them, with the default thresholds
// Cyclone's loopback configuration allows 33 participants per host (MaxAutoParticipantIndex 32);
// 32 hubs plus this program and hubctl need more, so this run raises it (see kMaxParticipantIndex).
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "bench_common.h"
#include "dock.h"
#include "proc_stats.h"
#include "raw_dds.h"

namespace hubrt::bench {
namespace {

constexpr int kMaxParticipantIndex = 64;

std::string cyclone_xml() {
  return fmt::format(
      "<CycloneDDS><Domain id=\"any\"><General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
      "<AllowMulticast>false</AllowMulticast></General><Discovery><ParticipantIndex>auto</ParticipantIndex>"
      "<MaxAutoParticipantIndex>{}</MaxAutoParticipantIndex><Peers><Peer address=\"127.0.0.1\"/></Peers>"
      "</Discovery></Domain></CycloneDDS>",
      kMaxParticipantIndex);
}

// A copy of the shipped Dock ECU configuration with its own name, namespace and rate.
Expected<std::string> write_hub_file(const std::filesystem::path& dir, int index, double rate) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(source_dir() + "/hubs/dock_ecu/dock_ecu.yaml");
  } catch (const YAML::Exception& e) {
    return make_error(ErrorCode::kIo, fmt::format("hubs/dock_ecu/dock_ecu.yaml: {}", e.what()));
  }
  root["name"] = fmt::format("dock_{:02}", index);
  root["namespace"] = fmt::format("/h{:02}", index);
  root["rate_hz"] = rate;
  const auto path = dir / fmt::format("dock_{:02}.yaml", index);
  std::ofstream out(path);
  out << root << "\n";
  if (!out) return make_error(ErrorCode::kIo, fmt::format("cannot write {}", path.string()));
  return path.string();
}

std::string state_topic(int index) {
  return fmt::format("rt/h{:02}/dock_{:02}/dock/state", index, index);
}

Expected<nlohmann::ordered_json> measure(int hubs, double rate, double cpu_window_s,
                                         const std::filesystem::path& dir,
                                         const test_support::Environment& env) {
  auto participant = raw_participant(domain_from_environment());
  if (!participant) return std::move(participant).error();
  std::vector<dds_entity_t> readers;
  for (int i = 1; i <= hubs; ++i) {
    auto reader = raw_reader(*participant, hub_msgs_msg_dds__DockState__desc, state_topic(i));
    if (!reader) return std::move(reader).error();
    readers.push_back(*reader);
  }
  std::vector<std::string> files;
  for (int i = 1; i <= hubs; ++i) {
    auto file = write_hub_file(dir, i, rate);
    if (!file) return std::move(file).error();
    files.push_back(*file);
  }
  std::vector<test_support::ChildProcess> children;
  const double t0 = mono_now();
  for (const std::string& file : files) {
    auto child = start_hubd({"--hub", file}, env);
    if (!child) return std::move(child).error();
    children.push_back(std::move(*child));
  }
  double discovered = -1;
  double heard = -1;
  std::vector<bool> got(readers.size(), false);
  while ((discovered < 0 || heard < 0) && mono_now() - t0 < 60) {
    std::size_t matched = 0;
    std::size_t received = 0;
    for (std::size_t i = 0; i < readers.size(); ++i) {
      dds_subscription_matched_status_t status{};
      if (dds_get_subscription_matched_status(readers[i], &status) >= 0 && status.current_count > 0)
        ++matched;
      void* samples[16] = {};
      dds_sample_info_t infos[16];
      const dds_return_t n = dds_take(readers[i], samples, infos, 16, 16);
      if (n > 0) {
        got[i] = true;
        dds_return_loan(readers[i], samples, n);
      }
      if (got[i]) ++received;
    }
    if (discovered < 0 && matched == readers.size()) discovered = mono_now() - t0;
    if (heard < 0 && received == readers.size()) heard = mono_now() - t0;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  dds_delete(*participant);  // from here on only the hubs and hubctl
  if (heard < 0)
    return make_error(ErrorCode::kTimeout, fmt::format("not every one of {} hubs was heard in 60 s", hubs));

  std::vector<ProcSample> before;
  for (const auto& child : children) {
    auto sample = read_proc(child.pid());
    if (!sample) return std::move(sample).error();
    before.push_back(*sample);
  }
  const double start = mono_now();
  std::this_thread::sleep_for(std::chrono::duration<double>(cpu_window_s));
  const double elapsed = mono_now() - start;
  double cpu = 0;
  double rss = 0;
  for (std::size_t i = 0; i < children.size(); ++i) {
    auto after = read_proc(children[i].pid());
    if (!after) return std::move(after).error();
    cpu += cpu_percent(before[i], *after, elapsed);
    rss += after->rss_mb;
  }

  std::vector<std::string> args = {
      "conformance", "--json", "--parallel",        "--dds-config", cyclone_xml(), "--duration", "3",
      "--hold",      "0.5",    "--latency-samples", "20",           "--timeout",   "30"};
  for (int i = 1; i <= hubs; ++i) {
    args.emplace_back("--hub");
    args.push_back(fmt::format("dock_{:02}", i));
  }
  auto suite = test_support::ChildProcess::start(hubctl_path(), args, env);
  if (!suite) return std::move(suite).error();
  auto status = suite->wait(std::chrono::seconds(300));
  for (auto& child : children) stop(child);
  if (!status) return make_error(ErrorCode::kTimeout, "hubctl conformance did not finish in 300 s");
  const auto report = nlohmann::json::parse(suite->stdout_text(), nullptr, false);
  std::size_t conforming = 0;
  std::size_t tested = 0;
  std::map<std::string, std::size_t> failed_checks;
  if (!report.is_discarded()) {
    for (const auto& target : report["targets"]) {
      ++tested;
      if (target["passed"] == true) ++conforming;
      for (const auto& check : target["checks"]) {
        if (check["verdict"] == "FAIL") ++failed_checks[check["check"].get<std::string>()];
      }
    }
  }

  nlohmann::ordered_json out;
  out["hubs"] = hubs;
  out["rate_hz"] = rate;
  out["discovery_ms"] = discovered * 1e3;
  out["all_heard_ms"] = heard * 1e3;
  out["cpu_total_pct"] = cpu;
  out["cpu_per_hub_pct"] = cpu / hubs;
  out["rss_per_hub_mb"] = rss / hubs;
  out["tested"] = tested;
  out["conforming"] = conforming;
  out["failed_checks"] = failed_checks;
  out["hubctl_exit"] = status->describe();
  return out;
}

int run(const std::string& out_file, const std::vector<int>& sizes, double rate, double cpu_window_s) {
  auto domain = join_private_domain();
  if (!domain) return fmt::print(stderr, "{}\n", domain.error().message), 1;
  setenv("CYCLONEDDS_URI", cyclone_xml().c_str(), 1);  // NOLINT(concurrency-mt-unsafe): no threads yet
  const test_support::Environment env = {{"CYCLONEDDS_URI", cyclone_xml()}};
  const auto dir = std::filesystem::temp_directory_path() / fmt::format("hubrt-bench-scale-{}", getpid());
  std::filesystem::create_directories(dir);
  nlohmann::ordered_json result;
  result["max_auto_participant_index"] = kMaxParticipantIndex;
  result["sizes"] = nlohmann::ordered_json::array();
  int code = 0;
  for (const int hubs : sizes) {
    progress(fmt::format("scale: {} hub(s) at {} Hz: discovery, CPU, conformance", hubs, rate));
    auto measured = measure(hubs, rate, cpu_window_s, dir, env);
    if (!measured) {
      fmt::print(stderr, "{} hubs: {}\n", hubs, measured.error().message);
      code = 1;
      break;
    }
    progress(fmt::format("scale {}: discovery {:.0f} ms, CPU {:.1f} % total, {}/{} conforming", hubs,
                         (*measured)["discovery_ms"].get<double>(),
                         (*measured)["cpu_total_pct"].get<double>(),
                         (*measured)["conforming"].get<std::size_t>(), hubs));
    result["sizes"].push_back(std::move(*measured));
  }
  std::filesystem::remove_all(dir);
  if (auto ok = write_json(out_file, result); !ok) return fmt::print(stderr, "{}\n", ok.error().message), 1;
  return code;
}

}  // namespace
}  // namespace hubrt::bench

int main(int argc, char** argv) {
  CLI::App app{"1, 8, 32 hubs on one host: discovery, CPU, conformance"};
  std::string out = "scale.json";
  std::vector<int> sizes{1, 8, 32};
  double rate = 100;
  double cpu_window_s = 5;
  app.add_option("--out", out, "Result file (JSON)");
  app.add_option("--sizes", sizes, "Numbers of hubs");
  app.add_option("--rate", rate, "Each hub's rate in Hz");
  app.add_option("--cpu-seconds", cpu_window_s, "CPU measuring window");
  CLI11_PARSE(app, argc, argv);
  return hubrt::bench::run(out, sizes, rate, cpu_window_s);
}
