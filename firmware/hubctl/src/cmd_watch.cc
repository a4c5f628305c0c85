// hubctl watch: every hub State on the domain in one live table — the operator's view of the
// station. New hubs appear as they are discovered; a node that stops publishing turns "silent".
// With --from FILE.mcap the same table is played from a recording, at its pace (--rate).
#include <unistd.h>

#include <set>
#include <thread>

#include <fmt/format.h>

#include "hubrt/msgs/json.h"

#include "commands.h"
#include "plant_tap.h"
#include "recording_source.h"
#include "render.h"
#include "sample_decoder.h"
#include "session.h"
#include "station_tap.h"
#include "station_watch.h"

namespace hubrt::hubctl {
namespace {

struct WatchOptions {
  PlantOptions plant;
  double refresh_hz = 4.0;
  double duration_s = 0;          // 0 = until stopped
  bool plain = false;             // no screen redraw (logs, pipes)
  std::vector<std::string> from;  // recordings to play instead of the domain
  double rate = 1.0;              // their pace
};

// The node-specific part of a State in one line: every field after the common ones.
std::string details(const nlohmann::ordered_json& state) {
  static const std::set<std::string> kCommon = {"header", "name",      "echo",      "fresh_msg",
                                                "t_plus", "got_reset", "error_list"};
  std::string out;
  for (const auto& [key, value] : state.items()) {
    if (kCommon.count(key) != 0) continue;
    std::string text;
    if (value.is_array() && !value.empty() && value.front().is_object() && value.front().contains("name")) {
      for (const auto& item : value) {  // e.g. dock slots: "smart_tool=1"
        std::string flags;
        for (const auto& [k, v] : item.items()) {
          if (k != "name")
            flags += fmt::format("{}{}", flags.empty() ? "" : ",",
                                 v.is_boolean() ? (v.get<bool>() ? "1" : "0") : safe_dump(v));
        }
        text += fmt::format("{}{}={}", text.empty() ? "" : " ", item["name"].get<std::string>(), flags);
      }
    } else if (value.is_string()) {
      text = value.get<std::string>();
    } else if (value.is_number_float()) {
      text = fmt::format("{:g}", value.get<double>());
    } else if (value.is_null()) {
      text = "NaN";  // a float not measured (null in JSON)
    } else {
      text = safe_dump(value);
    }
    out += fmt::format("{}{}: {}", out.empty() ? "" : "  ", key, text);
  }
  return out;
}

void draw(const std::map<std::string, WatchedState>& watched, bool plain,
          std::chrono::steady_clock::time_point now) {
  std::string screen;
  if (!plain) screen += "\x1b[H\x1b[2J";
  screen += fmt::format("{:<34} {:<5} {:<15} {:>7} {:<16} {}\n", "STATE TOPIC", "FRESH", "LIFECYCLE",
                        "T+ [s]", "ECHO ACTION", "STATE / ERRORS");
  for (const auto& [topic, w] : watched) {
    if (w.received == 0) {
      screen += fmt::format("{:<34} (discovered, no State yet)\n", topic);
      continue;
    }
    const bool silent = w.silent(now);
    const auto& s = w.last;
    const std::string fresh = silent ? "SILENT" : (s.value("fresh_msg", false) ? "yes" : "no");
    std::string action = s.contains("echo") ? s["echo"].value("action", "") : "";
    if (action.empty()) action = "-";
    screen += fmt::format("{:<34} {:<5} {:<15} {:>7.1f} {:<16} {}\n", topic, fresh, lifecycle(s),
                          number_or_nan(s, "t_plus"), action, details(s));
    if (s.contains("error_list")) {
      for (const auto& e : s["error_list"])
        screen += fmt::format("{:<34}   ! {}\n", "", e.get<std::string>());
    }
  }
  fmt::print("{}", screen);
  if (plain) fmt::print("\n");
  std::fflush(stdout);
}

int run_watch(const WatchOptions& options) {
  install_stop_handler();
  const bool live = options.from.empty();
  // Live: one participant per station's domain (plant_session.h); a recording needs none.
  std::vector<PlantMember> members;
  if (live) {
    auto joined = join_plant(options.plant, "hubctl");
    if (!joined) {
      fmt::print(stderr, "hubctl watch: {}\n", joined.error().message);
      return kExitUsage;
    }
    members = std::move(*joined);
  }
  // The source of States: the tap on the domains, or the recording.
  std::unique_ptr<PlantTap> tap;
  std::unique_ptr<TapSource> source;
  if (live) {
    TapOptions tap_options;
    tap_options.filter = &is_state_topic;
    auto started = PlantTap::start(members, tap_options);
    if (!started) {
      fmt::print(stderr, "hubctl watch: {}\n", started.error().message);
      return kExitFailed;
    }
    tap = std::move(*started);
    source = tap->subscribe(10'000);
  } else {
    auto opened = RecordingSource::open(options.from, RecordingOptions{options.rate, 0, {}, &is_state_topic});
    if (!opened) {
      fmt::print(stderr, "hubctl watch: {}\n", opened.error().message);
      return kExitUsage;
    }
    source = std::move(*opened);
  }
  TapDecoder decoder("hubctl watch");
  StationWatch watch;
  const auto start = std::chrono::steady_clock::now();
  auto next_draw = start;
  const auto refresh = seconds(1.0 / options.refresh_hz);
  while (!stop_requested()) {
    const auto now = std::chrono::steady_clock::now();
    if (options.duration_s > 0 && now - start >= seconds(options.duration_s)) break;
    watch.drain(*source, decoder);
    const bool ended = source->finished();
    if (now >= next_draw || ended) {
      next_draw = now + refresh;
      draw(watch.states(), options.plain, now);
    }
    if (ended) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!source->problem().empty()) fmt::print(stderr, "hubctl watch: {}\n", source->problem());
  return watch.states().empty() ? kExitFailed : kExitOk;
}

}  // namespace

void add_watch_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<WatchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "watch", "Show every hub State on the domain (or on a plant's stations' domains) in one live table");
  cmd->add_option("--refresh", options->refresh_hz, "Screen refreshes per second")
      ->check(CLI::Range(0.1, 50.0));
  cmd->add_option("--duration", options->duration_s, "Stop after this many seconds (default: until Ctrl-C)");
  cmd->add_flag("--plain", options->plain, "Print tables one after another instead of redrawing the screen");
  cmd->add_option("--from", options->from,
                  "Play the States of a recording (hubctl record, a black box; the parts of a split one in "
                  "order: --from a_0.mcap --from a_1.mcap) instead of the domain")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--rate", options->rate, "With --from: the pace, as a factor of the recorded one")
      ->check(CLI::Range(0.01, 1000.0));
  add_plant_options(*cmd, options->plant);
  cmd->callback([options, &exit_code] {
    WatchOptions effective = *options;
    if (isatty(STDOUT_FILENO) == 0) effective.plain = true;
    exit_code = run_watch(effective);
  });
}

}  // namespace hubrt::hubctl
