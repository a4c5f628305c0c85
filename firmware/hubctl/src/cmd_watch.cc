// hubctl watch: every hub State on the domain in one live table — the operator's view of the
// station. New hubs appear as they are discovered; a node that stops publishing turns "silent".
#include <unistd.h>

#include <map>
#include <set>
#include <thread>

#include <fmt/format.h>

#include "hubrt/dds/discovery.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/ros_names.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/json.h"
#include "hubrt/runtime/lifecycle.h"

#include "commands.h"
#include "sample_decoder.h"
#include "session.h"

namespace hubrt::hubctl {
namespace {

struct WatchOptions {
  DomainOptions domain;
  double refresh_hz = 4.0;
  double duration_s = 0;  // 0 = until stopped
  bool plain = false;     // no screen redraw (logs, pipes)
};

// A State type is one with the common State fields.
bool is_state_type(const msgs::TypeInfo& type) {
  bool fresh = false;
  bool echo = false;
  for (const auto& field : type.fields) {
    fresh |= field.name == "fresh_msg";
    echo |= field.name == "echo";
  }
  return fresh && echo;
}

struct Watched {
  std::string topic;
  const msgs::TypeInfo* type = nullptr;
  std::optional<dds::UntypedTopic> dds_topic;
  std::optional<dds::UntypedReader> reader;
  std::optional<dds::UntypedSample> sample;
  std::optional<SampleDecoder> decoder;
  nlohmann::ordered_json last;
  std::chrono::steady_clock::time_point last_seen{};
  std::size_t received = 0;
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
    } else {
      text = safe_dump(value);
    }
    out += fmt::format("{}{}: {}", out.empty() ? "" : "  ", key, text);
  }
  return out;
}

// The State header's lifecycle by name ("operational"), "-" when the State has none.
std::string lifecycle(const nlohmann::ordered_json& state) {
  if (!state.contains("header") || !state["header"].contains("lifecycle")) return "-";
  const auto& value = state["header"]["lifecycle"];
  if (!value.is_number_unsigned() || value.get<std::uint64_t>() > 255) return "unknown";
  return std::string(runtime::lifecycle_name(static_cast<std::uint8_t>(value.get<std::uint64_t>())));
}

void draw(const std::map<std::string, Watched>& watched, bool plain,
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
    const auto age = std::chrono::duration<double>(now - w.last_seen).count();
    const bool silent = age > 2.0;
    const auto& s = w.last;
    const std::string fresh = silent ? "SILENT" : (s.value("fresh_msg", false) ? "yes" : "no");
    std::string action = s.contains("echo") ? s["echo"].value("action", "") : "";
    if (action.empty()) action = "-";
    screen += fmt::format("{:<34} {:<5} {:<15} {:>7.1f} {:<16} {}\n", topic, fresh, lifecycle(s),
                          s.value("t_plus", 0.0), action, details(s));
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
  auto participant = join_domain(options.domain, "hubctl");
  if (!participant) {
    fmt::print(stderr, "hubctl watch: {}\n", participant.error().message);
    return kExitUsage;
  }
  std::map<std::string, Watched> watched;
  const auto start = std::chrono::steady_clock::now();
  auto next_discovery = start;
  auto next_draw = start;
  const auto refresh = seconds(1.0 / options.refresh_hz);
  while (!stop_requested()) {
    const auto now = std::chrono::steady_clock::now();
    if (options.duration_s > 0 && now - start >= seconds(options.duration_s)) break;
    if (now >= next_discovery) {
      next_discovery = now + std::chrono::milliseconds(500);
      auto snapshot = dds::discover(*participant);
      if (snapshot) {
        for (const auto& topic : snapshot->topics()) {
          if (topic.writers <= topic.local_writers) continue;
          const msgs::TypeInfo* type = msgs::all_types().find_by_dds_name(topic.type_name);
          const auto ros = dds::dds_to_ros_topic(topic.topic_name);
          if (type == nullptr || !ros || !is_state_type(*type) || watched.count(*ros) != 0) continue;
          Watched w;
          w.topic = *ros;
          w.type = type;
          auto t = dds::UntypedTopic::create(*participant, *type->descriptor, *ros);
          if (!t) continue;
          w.dds_topic.emplace(std::move(*t));
          auto r = dds::UntypedReader::create(*participant, *w.dds_topic);
          if (!r) continue;
          w.reader.emplace(std::move(*r));
          w.sample.emplace(*type->descriptor);
          w.decoder.emplace("hubctl watch", *ros);
          watched.emplace(*ros, std::move(w));
        }
      }
    }
    for (auto& [topic, w] : watched) {
      while (true) {
        const Result<bool> taken = w.reader->take_next(w.sample->data());
        if (!taken.is_ok() || !taken.value()) break;
        // A sample that cannot be shown is reported and skipped; the others keep coming.
        auto value = w.decoder->decode(*w.type, w.sample->data());
        if (!value) continue;
        w.last = std::move(*value);
        w.last_seen = std::chrono::steady_clock::now();
        ++w.received;
      }
    }
    if (now >= next_draw) {
      next_draw = now + refresh;
      draw(watched, options.plain, now);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return watched.empty() ? kExitFailed : kExitOk;
}

}  // namespace

void add_watch_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<WatchOptions>();
  CLI::App* cmd = app.add_subcommand("watch", "Show every hub State on the domain in one live table");
  cmd->add_option("--refresh", options->refresh_hz, "Screen refreshes per second")
      ->check(CLI::Range(0.1, 50.0));
  cmd->add_option("--duration", options->duration_s, "Stop after this many seconds (default: until Ctrl-C)");
  cmd->add_flag("--plain", options->plain, "Print tables one after another instead of redrawing the screen");
  add_domain_options(*cmd, options->domain);
  cmd->callback([options, &exit_code] {
    WatchOptions effective = *options;
    if (isatty(STDOUT_FILENO) == 0) effective.plain = true;
    exit_code = run_watch(effective);
  });
}

}  // namespace hubrt::hubctl
