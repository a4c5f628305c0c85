// Many hubs on one host: for each size (1, 8, 32, 64 by default) start that many Dock ECU hubs at
// the shipped Dock ECU's 10 Hz, each with its own name and ROS namespace (so that commands address
// one hub alone), and measure
//   discovery   spawn of the first hub -> a waiting planner matched every hub's State writer
//   all heard   ... -> that planner received a State from every hub
//   after last  spawn of the last hub -> that planner received a State from every hub
//   start CPU   CPU time the hubs spent until then (start-up and discovery), all hubs together
//   late planner  a planner that joins when every hub is up: its start -> a State from every hub
//   CPU, RSS    of all hubs together over a window, and per hub
//   conforming  `hubctl conformance --parallel` against all of them, with the default thresholds
//   exited      hubs that ended by themselves (a crash) before they were stopped
// Every process uses hubrt's loopback configuration (dds::loopback_config_xml), as hubd --loopback
// and hubctl --loopback do: it admits 64 hubs, this program and hubctl on one host.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <thread>
#include <utility>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "hubrt/dds/domain.h"

#include "bench_common.h"
#include "dock.h"
#include "proc_stats.h"
#include "raw_dds.h"

namespace hubrt::bench {
namespace {

// Runs of the late planner: each a new participant, its readers matched and a State from each hub.
constexpr int kLatePlannerRuns = 3;
// Generous: 64 hubs starting at once on a loaded 2-core host; reached only when something broke.
constexpr double kDiscoveryBoundS = 60;

// /proc/loadavg's 1, 5 and 15 minute figures: the machine is shared, every figure says its load.
std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one;
  std::string five;
  std::string fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
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

// A planner's view of the hubs: one State reader per hub on its own participant.
struct Planner {
  dds_entity_t participant = 0;
  std::vector<dds_entity_t> readers;
  std::vector<bool> heard;
};

Expected<Planner> join_planner(int hubs) {
  auto participant = raw_participant(domain_from_environment());
  if (!participant) return std::move(participant).error();
  Planner planner{*participant, {}, std::vector<bool>(static_cast<std::size_t>(hubs), false)};
  for (int i = 1; i <= hubs; ++i) {
    auto reader = raw_reader(planner.participant, hub_msgs_msg_dds__DockState__desc, state_topic(i));
    if (!reader) {
      dds_delete(planner.participant);
      return std::move(reader).error();
    }
    planner.readers.push_back(*reader);
  }
  return planner;
}

// Seconds from `t0` until the planner matched every hub's State writer and until it received a
// State from each; kDiscoveryBoundS at most (then the missing ones are negative).
std::pair<double, double> wait_for_all(Planner& planner, double t0) {
  double matched_at = -1;
  double heard_at = -1;
  while ((matched_at < 0 || heard_at < 0) && mono_now() - t0 < kDiscoveryBoundS) {
    std::size_t matched = 0;
    std::size_t heard = 0;
    for (std::size_t i = 0; i < planner.readers.size(); ++i) {
      dds_subscription_matched_status_t status{};
      if (dds_get_subscription_matched_status(planner.readers[i], &status) >= 0 && status.current_count > 0)
        ++matched;
      void* samples[16] = {};
      dds_sample_info_t infos[16];
      const dds_return_t n = dds_take(planner.readers[i], samples, infos, 16, 16);
      if (n > 0) {
        planner.heard[i] = true;
        dds_return_loan(planner.readers[i], samples, n);
      }
      if (planner.heard[i]) ++heard;
    }
    if (matched_at < 0 && matched == planner.readers.size()) matched_at = mono_now() - t0;
    if (heard_at < 0 && heard == planner.readers.size()) heard_at = mono_now() - t0;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return {matched_at, heard_at};
}

// A planner that starts when every hub is up: from creating its participant to a State from each.
Expected<nlohmann::ordered_json> late_planner(int hubs) {
  std::vector<double> matched;
  std::vector<double> heard;
  for (int run = 0; run < kLatePlannerRuns; ++run) {
    const double t0 = mono_now();
    auto planner = join_planner(hubs);
    if (!planner) return std::move(planner).error();
    const auto [m, h] = wait_for_all(*planner, t0);
    dds_delete(planner->participant);
    if (h < 0)
      return make_error(ErrorCode::kTimeout, fmt::format("a late planner did not hear {} hubs", hubs));
    matched.push_back(m * 1e3);
    heard.push_back(h * 1e3);
  }
  nlohmann::ordered_json out;
  out["runs"] = kLatePlannerRuns;
  out["matched_ms"] = matched;
  out["heard_ms"] = heard;
  return out;
}

Expected<nlohmann::ordered_json> measure(int hubs, double rate, double cpu_window_s,
                                         const std::filesystem::path& dir,
                                         const test_support::Environment& env) {
  auto planner = join_planner(hubs);
  if (!planner) return std::move(planner).error();
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
  const double last_spawned = mono_now() - t0;
  const auto [discovered, heard] = wait_for_all(*planner, t0);
  // What starting and discovering cost the hubs: with N processes on 2 cores the wall time from
  // the last start cannot be less than this CPU time / 2.
  double start_cpu_s = 0;
  for (const auto& child : children) {
    if (auto sample = read_proc(child.pid())) start_cpu_s += sample->cpu_s;
  }
  dds_delete(planner->participant);  // from here on only the hubs, the late planners and hubctl
  if (heard < 0)
    return make_error(ErrorCode::kTimeout,
                      fmt::format("not every one of {} hubs was heard in {} s", hubs, kDiscoveryBoundS));
  auto late = late_planner(hubs);
  if (!late) return std::move(late).error();

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

  std::vector<std::string> args = {"conformance",       "--json", "--parallel", "--loopback",
                                   "--duration",        "3",      "--hold",     "0.5",
                                   "--latency-samples", "20",     "--timeout",  "30"};
  for (int i = 1; i <= hubs; ++i) {
    args.emplace_back("--hub");
    args.push_back(fmt::format("dock_{:02}", i));
  }
  const double suite_start = mono_now();
  auto suite = test_support::ChildProcess::start(hubctl_path(), args, env);
  if (!suite) return std::move(suite).error();
  auto status = suite->wait(std::chrono::seconds(300));
  const double suite_s = mono_now() - suite_start;
  std::size_t exited = 0;  // ended before being stopped: a hub that crashed
  for (auto& child : children) {
    if (child.wait(std::chrono::milliseconds(0))) {
      ++exited;
      fmt::print(stderr, "a hub ended by itself: {}\n", child.stderr_text());
    } else {
      stop(child);
    }
  }
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
  out["last_spawned_ms"] = last_spawned * 1e3;
  out["heard_after_last_spawn_ms"] = (heard - last_spawned) * 1e3;
  out["start_cpu_s"] = start_cpu_s;
  out["late_planner"] = *late;
  out["cpu_total_pct"] = cpu;
  out["cpu_per_hub_pct"] = cpu / hubs;
  out["rss_per_hub_mb"] = rss / hubs;
  out["tested"] = tested;
  out["conforming"] = conforming;
  out["failed_checks"] = failed_checks;
  out["hubctl_exit"] = status->describe();
  out["conformance_s"] = suite_s;
  out["hubs_exited"] = exited;
  return out;
}

// One measurement: this many hubs at this rate.
struct Size {
  int hubs = 0;
  double rate_hz = 0;
};

int run(const std::string& out_file, const std::vector<Size>& sizes, double cpu_window_s) {
  auto domain = join_private_domain();
  if (!domain) return fmt::print(stderr, "{}\n", domain.error().message), 1;
  const std::string cyclone_xml = dds::loopback_config_xml();
  setenv("CYCLONEDDS_URI", cyclone_xml.c_str(), 1);  // NOLINT(concurrency-mt-unsafe): no threads yet
  const test_support::Environment env = {{"CYCLONEDDS_URI", cyclone_xml}};
  const auto dir = std::filesystem::temp_directory_path() / fmt::format("hubrt-bench-scale-{}", getpid());
  std::filesystem::create_directories(dir);
  nlohmann::ordered_json result;
  result["loopback_participants_per_host"] = dds::kLoopbackParticipantsPerHost;
  result["load_start"] = load_average();
  result["sizes"] = nlohmann::ordered_json::array();
  int code = 0;
  for (const auto [hubs, rate] : sizes) {
    progress(fmt::format("scale: {} hub(s) at {} Hz: discovery, CPU, conformance", hubs, rate));
    auto measured = measure(hubs, rate, cpu_window_s, dir, env);
    if (!measured) {
      fmt::print(stderr, "{} hubs: {}\n", hubs, measured.error().message);
      code = 1;
      break;
    }
    progress(fmt::format(
        "scale {}: all heard {:.0f} ms after the last start, CPU {:.1f} % total, {}/{} "
        "conforming",
        hubs, (*measured)["heard_after_last_spawn_ms"].get<double>(),
        (*measured)["cpu_total_pct"].get<double>(), (*measured)["conforming"].get<std::size_t>(), hubs));
    result["sizes"].push_back(std::move(*measured));
  }
  result["load_end"] = load_average();
  std::filesystem::remove_all(dir);
  if (auto ok = write_json(out_file, result); !ok) return fmt::print(stderr, "{}\n", ok.error().message), 1;
  return code;
}

}  // namespace
}  // namespace hubrt::bench

int main(int argc, char** argv) {
  CLI::App app{"1, 8, 32, 64 hubs on one host: discovery, CPU, conformance"};
  std::string out = "scale.json";
  std::vector<int> sizes{1, 8, 32, 64};
  double rate = 10;  // the shipped Dock ECU's rate (hubs/dock_ecu/dock_ecu.yaml)
  std::vector<int> fast_sizes{32};
  double fast_rate = 100;
  double cpu_window_s = 5;
  app.add_option("--out", out, "Result file (JSON)");
  app.add_option("--sizes", sizes, "Numbers of hubs");
  app.add_option("--rate", rate, "Each hub's rate in Hz");
  app.add_option("--fast-sizes", fast_sizes, "Numbers of hubs also measured at --fast-rate");
  app.add_option("--fast-rate", fast_rate, "The second rate in Hz (0: none)");
  app.add_option("--cpu-seconds", cpu_window_s, "CPU measuring window");
  CLI11_PARSE(app, argc, argv);
  std::vector<hubrt::bench::Size> all;
  for (const int hubs : sizes) all.push_back({hubs, rate});
  if (fast_rate > 0) {
    for (const int hubs : fast_sizes) all.push_back({hubs, fast_rate});
  }
  return hubrt::bench::run(out, all, cpu_window_s);
}
