// hubctl conformance: the heartbeat conformance suite against live hubs, from the wire only —
// rate, jitter, sequence, first State, command -> echo latency, fresh_msg / t_plus, watchdog and
// safe state, no stale re-apply, reset. A table (or --json) and exit code 1 if anything fails.
#include <map>
#include <set>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hubrt/dds/discovery.h"
#include "hubrt/dds/domain.h"
#include "hubrt/dds/ros_names.h"
#include "hubrt/msgs/all_types.h"

#include "commands.h"
#include "conformance_report.h"
#include "conformance_session.h"
#include "launched_hub.h"
#include "sample_decoder.h"
#include "session.h"

namespace hubrt::hubctl {
namespace {

struct ConformanceOptions {
  DomainOptions domain;
  std::vector<std::string> hubs;
  std::vector<std::string> topics;
  std::vector<std::string> profiles;
  std::string hub_type;
  std::optional<double> rate_hz;
  std::optional<double> command_timeout_ms;
  std::string thresholds_file;
  std::vector<std::string> threshold_sets;
  bool print_thresholds = false;
  double heartbeat_s = 5.0;
  double hold_s = 1.0;
  std::size_t latency_samples = 100;
  std::optional<double> repeat_ms;
  std::string phases;
  std::string launch;
  double wait_s = 2.0;
  double diagnostics_wait_s = 2.5;
  bool parallel = false;
  bool json = false;
  bool verbose = false;
};

struct StateTopic {
  std::string ros_name;
  const msgs::TypeInfo* type = nullptr;
};

// Every State topic someone else writes, by ROS name.
Expected<std::map<std::string, StateTopic>> state_topics(const dds::Participant& participant) {
  auto snapshot = dds::discover(participant);
  if (!snapshot) return std::move(snapshot).error();
  std::map<std::string, StateTopic> out;
  for (const dds::TopicSummary& topic : snapshot->topics()) {
    if (topic.writers <= topic.local_writers) continue;
    const msgs::TypeInfo* type = msgs::all_types().find_by_dds_name(topic.type_name);
    const auto ros = dds::dds_to_ros_topic(topic.topic_name);
    if (type == nullptr || !ros || !is_state_type(*type)) continue;
    out[*ros] = StateTopic{*ros, type};
  }
  return out;
}

std::string hub_of(const StateTopic& topic) {
  const auto layout = is_hub_state_type(*topic.type) ? TargetLayout::kHub : TargetLayout::kNodeType;
  auto parts = split_state_topic(topic.ros_name, layout);
  return parts ? parts->hub_name : std::string();
}

using EarlyStreams = std::map<std::string, StateStream>;

// Subscribes to every State topic as soon as discovery shows it and takes what arrived, so that
// the first State of a launched hub is timed when it comes, not when the suite gets to it.
void listen_early(const dds::Participant& participant, const std::map<std::string, StateTopic>& seen,
                  EarlyStreams& early) {
  for (const auto& [name, topic] : seen) {
    if (early.contains(name)) continue;
    auto stream = StateStream::open(participant, name, *topic.type);
    if (stream) early.emplace(name, std::move(*stream));
  }
  for (auto& [name, stream] : early) {
    if (!stream.pump(0.0).is_ok()) continue;  // a failing take shows again when the session runs
  }
}

// The State topics under test, once discovery has found what was asked for.
Expected<std::vector<StateTopic>> select_topics(const dds::Participant& participant,
                                                const ConformanceOptions& options, LaunchedHub* launched,
                                                EarlyStreams* early) {
  const double deadline = steady_seconds() + options.domain.timeout_s + (launched != nullptr ? 10.0 : 0.0);
  const bool all = options.hubs.empty() && options.topics.empty();
  std::set<std::string> last_seen;
  double stable_since = steady_seconds();
  for (;;) {
    auto seen = state_topics(participant);
    if (!seen) return std::move(seen).error();
    if (early != nullptr) listen_early(participant, *seen, *early);
    std::vector<StateTopic> chosen;
    std::set<std::string> missing;
    for (const std::string& topic : options.topics) {
      auto name = ros_topic(topic);
      if (!name) return std::move(name).error();
      const auto it = seen->find(*name);
      if (it == seen->end()) {
        missing.insert(*name);
      } else {
        chosen.push_back(it->second);
      }
    }
    for (const std::string& hub : options.hubs) {
      bool found = false;
      for (const auto& [name, topic] : *seen) {
        if (hub_of(topic) == hub) {
          chosen.push_back(topic);
          found = true;
        }
      }
      if (!found) missing.insert("hub " + hub);
    }
    std::set<std::string> names;
    for (const auto& [name, topic] : *seen) names.insert(name);
    if (names != last_seen) {
      last_seen = names;
      stable_since = steady_seconds();
    }
    if (all && steady_seconds() - stable_since >= options.wait_s) {
      // Every hub's State topic: not the simulation's (hubsim's station State is no hub).
      for (const auto& [name, topic] : *seen) {
        if (is_hub_state_topic(name)) chosen.push_back(topic);
      }
      if (!chosen.empty()) return chosen;
    }
    if (!all && missing.empty()) {
      std::sort(chosen.begin(), chosen.end(),
                [](const auto& a, const auto& b) { return a.ros_name < b.ros_name; });
      chosen.erase(std::unique(chosen.begin(), chosen.end(),
                               [](const auto& a, const auto& b) { return a.ros_name == b.ros_name; }),
                   chosen.end());
      return chosen;
    }
    if (launched != nullptr) {
      if (const std::string end = launched->ended(); !end.empty())
        return make_error(ErrorCode::kUnavailable,
                          fmt::format("the launched hub ended ({}) before it was found", end));
    }
    if (steady_seconds() >= deadline || stop_requested()) {
      return make_error(
          ErrorCode::kNotFound,
          fmt::format("not found on domain {}: {}; State topics seen: {}", participant.domain_id(),
                      all ? std::string("any State topic") : fmt::format("{}", fmt::join(missing, ", ")),
                      names.empty() ? std::string("none") : fmt::format("{}", fmt::join(names, ", "))));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(launched != nullptr ? 5 : 50));
  }
}

// A command topic shared by several nodes of the same name reaches all of them: none of them can
// be commanded alone, so none can be tested.
void check_addressing(const std::vector<Target>& targets, std::vector<TargetReport>& reports) {
  std::map<std::pair<std::string, std::string>, std::vector<std::string>> by_address;
  for (const Target& t : targets) {
    if (!t.command_topic.empty()) by_address[{t.command_topic, t.target_name}].push_back(t.hub_name);
  }
  for (TargetReport& report : reports) {
    const Target& t = report.target;
    if (t.command_topic.empty()) continue;
    const auto& hubs = by_address[{t.command_topic, t.target_name}];
    if (hubs.size() > 1) {
      report.checks.push_back(
          failed("addressing", "commands address this node alone",
                 fmt::format("'{}' on {} is a node of {} hubs ({}): give each hub its own "
                             "namespace",
                             t.target_name, t.command_topic, hubs.size(), fmt::join(hubs, ", "))));
    }
  }
}

Expected<std::set<std::string, std::less<>>> parse_phases(const std::string& text) {
  std::set<std::string, std::less<>> phases;
  if (text.empty()) return std::set<std::string, std::less<>>(kPhases.begin(), kPhases.end());
  std::string_view rest = text;
  while (!rest.empty()) {
    const auto comma = rest.find(',');
    const std::string_view phase = rest.substr(0, comma);
    if (std::find(kPhases.begin(), kPhases.end(), phase) == kPhases.end()) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("unknown phase '{}' (phases: {})", phase, fmt::join(kPhases, ", ")));
    }
    phases.insert(std::string(phase));
    rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
  }
  return phases;
}

std::vector<std::pair<std::string, std::string>> launch_environment(const ConformanceOptions& options,
                                                                    std::uint32_t domain_id) {
  std::vector<std::pair<std::string, std::string>> env;
  env.emplace_back(dds::kDomainIdEnvVar, std::to_string(domain_id));
  if (options.domain.loopback) env.emplace_back("CYCLONEDDS_URI", dds::loopback_config_xml());
  if (!options.domain.dds_config.empty()) env.emplace_back("CYCLONEDDS_URI", options.domain.dds_config);
  return env;
}

int usage_error(const std::string& message) {
  fmt::print(stderr, "hubctl conformance: {}\n", message);
  return kExitUsage;
}

int run_conformance(const ConformanceOptions& options) {
  Thresholds thresholds = default_thresholds();
  if (!options.thresholds_file.empty()) {
    if (auto ok = load_thresholds_file(options.thresholds_file, thresholds); !ok)
      return usage_error(ok.error().message);
  }
  for (const std::string& assignment : options.threshold_sets) {
    if (auto ok = apply_threshold_assignment(assignment, thresholds); !ok)
      return usage_error(ok.error().message);
  }
  if (options.print_thresholds) {
    fmt::print("{}", describe_thresholds(thresholds));
    return kExitOk;
  }
  auto phases = parse_phases(options.phases);
  if (!phases) return usage_error(phases.error().message);
  ProfileBook profiles;
  for (const std::string& file : options.profiles) {
    if (auto ok = profiles.add_file(file); !ok) return usage_error(ok.error().message);
  }
  install_stop_handler();
  auto participant = join_domain(options.domain, "hubctl-conformance");
  if (!participant) return usage_error(participant.error().message);

  std::optional<LaunchedHub> launched;
  if (!options.launch.empty()) {
    auto hub = LaunchedHub::start(options.launch, launch_environment(options, participant->domain_id()));
    if (!hub) return usage_error(hub.error().message);
    launched.emplace(std::move(*hub));
  }
  EarlyStreams early;
  auto topics =
      select_topics(*participant, options, launched ? &*launched : nullptr, launched ? &early : nullptr);
  if (!topics) {
    fmt::print(stderr, "hubctl conformance: {}\n", topics.error().message);
    return kExitFailed;
  }
  std::set<std::string> hub_names;
  for (const StateTopic& topic : *topics) hub_names.insert(hub_of(topic));
  auto diagnostics = listen_for_diagnostics(*participant, hub_names, options.diagnostics_wait_s);
  if (!diagnostics) return usage_error(diagnostics.error().message);

  TargetOverrides overrides{options.rate_hz, options.command_timeout_ms, options.hub_type};
  std::vector<Target> targets;
  std::vector<TargetReport> reports;
  for (const StateTopic& topic : *topics) {
    targets.push_back(resolve_target(topic.ros_name, *topic.type, *diagnostics, profiles, overrides));
    reports.push_back(TargetReport{targets.back(), {}});
  }
  check_addressing(targets, reports);

  SessionOptions session_options;
  session_options.heartbeat_s = options.heartbeat_s;
  session_options.hold_s = options.hold_s;
  session_options.latency_samples = options.latency_samples;
  if (options.repeat_ms) session_options.repeat_s = *options.repeat_ms / 1e3;
  session_options.discovery_timeout_s = options.domain.timeout_s;
  if (launched) session_options.launched_at_s = launched->started_at_s();
  session_options.phases = *phases;
  std::vector<std::unique_ptr<TargetSession>> sessions(targets.size());
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (!reports[i].checks.empty()) continue;  // not addressable: do not command it
    std::optional<StateStream> stream;
    if (auto it = early.find(targets[i].state_topic); it != early.end())
      stream.emplace(std::move(it->second));
    auto session =
        TargetSession::open(*participant, targets[i], thresholds, session_options, std::move(stream));
    if (!session) {
      reports[i].checks.push_back(failed("setup", "setting up", session.error().message));
      continue;
    }
    sessions[i] = std::move(*session);
  }
  const auto run_one = [&](std::size_t i) {
    if (sessions[i]) {
      for (CheckResult& r : sessions[i]->run()) reports[i].checks.push_back(std::move(r));
    }
  };
  if (options.parallel) {
    std::vector<std::thread> threads;
    threads.reserve(sessions.size());
    for (std::size_t i = 0; i < sessions.size(); ++i) threads.emplace_back(run_one, i);
    for (std::thread& t : threads) t.join();
  } else {
    for (std::size_t i = 0; i < sessions.size(); ++i) {
      if (!options.json) fmt::print(stderr, "testing {} ...\n", targets[i].state_topic);
      run_one(i);
    }
  }
  sessions.clear();
  early.clear();
  if (launched) {
    const std::string end = launched->ended();
    if (!end.empty()) {
      for (TargetReport& report : reports)
        report.checks.push_back(
            failed("hub_alive", "hub kept running", fmt::format("the hub ended: {}", end)));
    }
    launched->stop();
  }

  bool all_passed = !reports.empty();
  for (const TargetReport& report : reports) all_passed = all_passed && report.passed();
  if (options.json) {
    auto json = report_json(reports);
    json["domain"] = participant->domain_id();
    json["launched"] =
        options.launch.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(options.launch);
    fmt::print("{}\n", safe_dump(json, 2));
  } else {
    fmt::print("{}", render_report(reports, options.verbose));
  }
  if (stop_requested()) return kExitFailed;
  return all_passed ? kExitOk : kExitFailed;
}

}  // namespace

void add_conformance_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ConformanceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "conformance",
      "Run the heartbeat conformance suite against live hubs (exit code 1 if any check fails)");
  cmd->add_option("--hub", options->hubs,
                  "Test the State topics of this hub (repeatable; default: every hub)");
  cmd->add_option("--topic", options->topics, "Test this State topic (repeatable)");
  cmd->add_option("--profile", options->profiles,
                  "Conformance profile file (repeatable; default: hubs/<hub_type>/conformance.yaml)");
  cmd->add_option("--hub-type", options->hub_type, "Hub type, for hubs that publish no /diagnostics");
  cmd->add_option("--rate", options->rate_hz, "Expected State rate in Hz (default: from /diagnostics)")
      ->check(CLI::Range(0.01, 10000.0));
  cmd->add_option("--command-timeout", options->command_timeout_ms,
                  "Expected command timeout in ms (default: from /diagnostics)")
      ->check(CLI::Range(1.0, 3.6e6));
  cmd->add_option("--thresholds", options->thresholds_file, "YAML file of thresholds (KEY: VALUE)");
  cmd->add_option("--set", options->threshold_sets, "Threshold KEY=VALUE, over the file's (repeatable)");
  cmd->add_flag("--print-thresholds", options->print_thresholds,
                "Print every threshold with its value, default and reason, then exit");
  cmd->add_option("--duration", options->heartbeat_s, "Seconds of heartbeat to measure")
      ->check(CLI::Range(0.1, 86400.0));
  cmd->add_option("--hold", options->hold_s, "Seconds one command repeats while t_plus is followed")
      ->check(CLI::Range(0.05, 3600.0));
  cmd->add_option("--latency-samples", options->latency_samples,
                  "Commands written to measure the echo latency")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--repeat-ms", options->repeat_ms,
                  "The planner's repetition period in ms (default: command timeout / 5, at most 100)")
      ->check(CLI::Range(0.1, 60000.0));
  cmd->add_option("--phases", options->phases,
                  "Comma-separated phases to run: heartbeat,semantics,latency,watchdog,reset (default: all)");
  cmd->add_option("--launch", options->launch,
                  "Start the hub with this shell command and time its start to the first State; it gets "
                  "ROS_DOMAIN_ID (and CYCLONEDDS_URI for --loopback/--dds-config) and is stopped at the end");
  cmd->add_option(
         "--wait", options->wait_s,
         "Without --hub or --topic: seconds the set of State topics must stay unchanged before testing")
      ->check(CLI::Range(0.0, 600.0));
  cmd->add_option("--diagnostics-wait", options->diagnostics_wait_s,
                  "Seconds to listen on /diagnostics for the hubs' rate, timeout and node types")
      ->check(CLI::Range(0.0, 600.0));
  cmd->add_flag("--parallel", options->parallel, "Test every State topic at the same time (one thread each)");
  cmd->add_flag("--json", options->json, "Print the report as JSON");
  cmd->add_flag("--verbose,-v", options->verbose, "Show how each figure was measured, not only failures");
  add_domain_options(*cmd, options->domain);
  cmd->callback([options, &exit_code] { exit_code = run_conformance(*options); });
}

}  // namespace hubrt::hubctl
