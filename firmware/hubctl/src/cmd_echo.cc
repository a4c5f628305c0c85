// hubctl echo TOPIC: print every sample, human-readable or as JSON lines — as the tap takes them
// from the domain, or from a recording (--from FILE.mcap).
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hubrt/msgs/json.h"

#include "commands.h"
#include "recording_source.h"
#include "render.h"
#include "sample_decoder.h"
#include "session.h"
#include "station_tap.h"
#include "tap_decoder.h"

namespace hubrt::hubctl {
namespace {

struct EchoOptions {
  DomainOptions domain;
  std::string topic;
  std::string type;
  bool json = false;
  std::size_t count = 0;          // 0 = until stopped
  std::vector<std::string> from;  // recordings to read instead of the domain
};

// The samples of `ros_name` from the domain: the tap with a reader on that one topic, made at
// once as a subscriber's would be (before any writer is there).
Expected<std::unique_ptr<StationTap>> live_tap(const dds::Participant& participant,
                                               const std::string& ros_name, const EchoOptions& options) {
  auto type = topic_type(participant, ros_name, options.type, seconds(options.domain.timeout_s));
  if (!type) return std::move(type).error();
  TapOptions tap_options;
  tap_options.filter = [](std::string_view, const msgs::TypeInfo&) { return false; };
  tap_options.fixed.emplace_back(ros_name, *type);
  return StationTap::start(participant, std::move(tap_options));
}

int run_echo(const EchoOptions& options) {
  install_stop_handler();
  auto ros_name = ros_topic(options.topic);
  if (!ros_name) {
    fmt::print(stderr, "hubctl echo: {}\n", ros_name.error().message);
    return kExitUsage;
  }
  const bool live = options.from.empty();
  auto participant = live ? join_domain(options.domain, "hubctl") : isolated_participant("hubctl");
  if (!participant) {
    fmt::print(stderr, "hubctl echo: {}\n", participant.error().message);
    return kExitUsage;
  }
  std::unique_ptr<StationTap> tap;
  std::unique_ptr<TapSource> source;
  if (live) {
    auto started = live_tap(*participant, *ros_name, options);
    if (!started) {
      fmt::print(stderr, "hubctl echo: {}\n", started.error().message);
      return started.error().code == ErrorCode::kNotFound ||
                     started.error().code == ErrorCode::kInvalidArgument
                 ? kExitUsage
                 : kExitFailed;
    }
    tap = std::move(*started);
    source = tap->subscribe(100'000);
  } else {
    const std::string wanted = *ros_name;
    RecordingOptions recording;
    recording.filter = [wanted](std::string_view topic, const msgs::TypeInfo&) { return topic == wanted; };
    auto opened = RecordingSource::open(options.from, std::move(recording));
    if (!opened) {
      fmt::print(stderr, "hubctl echo: {}\n", opened.error().message);
      return kExitUsage;
    }
    source = std::move(*opened);
  }
  TapDecoder decoder("hubctl echo", *participant);
  std::size_t printed = 0;
  const auto deadline = std::chrono::steady_clock::now() + seconds(options.domain.timeout_s);
  while (!stop_requested() && (options.count == 0 || printed < options.count)) {
    auto event = source->next(std::chrono::milliseconds(50));
    if (!event) {
      if (source->finished()) break;
      if (live && printed == 0 && std::chrono::steady_clock::now() > deadline) {
        fmt::print(stderr, "hubctl echo: no sample on {} within {:.1f} s\n", *ros_name,
                   options.domain.timeout_s);
        return kExitFailed;
      }
      continue;
    }
    if (event->kind != TapEvent::Kind::kSample) continue;
    // A sample that cannot be shown is reported by the decoder and skipped; the stream goes on.
    const auto value = decoder.decode(*event->sample);
    if (!value) continue;
    if (options.json) {
      fmt::print("{}\n", safe_dump(*value));
    } else {
      fmt::print("--- {} ({})\n{}", *ros_name, event->topic->type_name, render_human(*value));
    }
    std::fflush(stdout);
    ++printed;
  }
  if (source->dropped() > 0)
    fmt::print(stderr, "hubctl echo: {} sample(s) not shown: the output could not keep up\n",
               source->dropped());
  if (!live) {
    if (!source->problem().empty()) fmt::print(stderr, "hubctl echo: {}\n", source->problem());
    if (printed == 0) {
      fmt::print(stderr, "hubctl echo: no message on {} in {}\n", *ros_name, fmt::join(options.from, ", "));
      return kExitFailed;
    }
  }
  return kExitOk;
}

}  // namespace

void add_echo_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<EchoOptions>();
  CLI::App* cmd = app.add_subcommand("echo", "Print the samples of a topic (a hub's State, a command)");
  cmd->add_option("topic", options->topic, "ROS topic name, e.g. /dock_ecu/dock/state")->required();
  cmd->add_option("--type", options->type,
                  "Message type, when no one on the domain has announced the topic yet");
  cmd->add_flag("--json", options->json, "One JSON object per line instead of the human form");
  cmd->add_option("--count,-n", options->count, "Stop after this many samples (default: until Ctrl-C)");
  cmd->add_option("--from", options->from,
                  "Read the topic from a recording (hubctl record, a black box) instead of the domain; "
                  "repeat for the parts of a split one, in order")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  add_domain_options(*cmd, options->domain);
  cmd->callback([options, &exit_code] { exit_code = run_echo(*options); });
}

}  // namespace hubrt::hubctl
