// hubctl echo TOPIC: print every sample, human-readable or as JSON lines.
#include <thread>

#include <fmt/format.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/msgs/json.h"

#include "commands.h"
#include "render.h"
#include "sample_decoder.h"
#include "session.h"

namespace hubrt::hubctl {
namespace {

struct EchoOptions {
  DomainOptions domain;
  std::string topic;
  std::string type;
  bool json = false;
  std::size_t count = 0;  // 0 = until stopped
};

int run_echo(const EchoOptions& options) {
  install_stop_handler();
  auto ros_name = ros_topic(options.topic);
  if (!ros_name) {
    fmt::print(stderr, "hubctl echo: {}\n", ros_name.error().message);
    return kExitUsage;
  }
  auto participant = join_domain(options.domain, "hubctl");
  if (!participant) {
    fmt::print(stderr, "hubctl echo: {}\n", participant.error().message);
    return kExitUsage;
  }
  auto type = topic_type(*participant, *ros_name, options.type, seconds(options.domain.timeout_s));
  if (!type) {
    fmt::print(stderr, "hubctl echo: {}\n", type.error().message);
    return kExitUsage;
  }
  const msgs::TypeInfo& info = **type;
  auto topic = dds::UntypedTopic::create(*participant, *info.descriptor, *ros_name);
  if (!topic) {
    fmt::print(stderr, "hubctl echo: {}\n", topic.error().message);
    return kExitFailed;
  }
  auto reader = dds::UntypedReader::create(*participant, *topic);
  if (!reader) {
    fmt::print(stderr, "hubctl echo: {}\n", reader.error().message);
    return kExitFailed;
  }
  dds::UntypedSample sample(*info.descriptor);
  SampleDecoder decoder("hubctl echo", *ros_name);
  std::size_t printed = 0;
  const auto deadline = std::chrono::steady_clock::now() + seconds(options.domain.timeout_s);
  while (!stop_requested() && (options.count == 0 || printed < options.count)) {
    const Result<bool> taken = reader->take_next(sample.data());
    if (!taken.is_ok()) {
      fmt::print(stderr, "hubctl echo: taking a sample failed: {}\n", to_string(taken.status().code()));
      return kExitFailed;
    }
    if (!taken.value()) {
      if (printed == 0 && std::chrono::steady_clock::now() > deadline) {
        fmt::print(stderr, "hubctl echo: no sample on {} within {:.1f} s\n", *ros_name,
                   options.domain.timeout_s);
        return kExitFailed;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    // A sample that cannot be shown is reported by the decoder and skipped; the stream goes on.
    const auto value = decoder.decode(info, sample.data());
    if (!value) continue;
    if (options.json) {
      fmt::print("{}\n", safe_dump(*value));
    } else {
      fmt::print("--- {} ({})\n{}", *ros_name, info.ros_name, render_human(*value));
    }
    std::fflush(stdout);
    ++printed;
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
  add_domain_options(*cmd, options->domain);
  cmd->callback([options, &exit_code] { exit_code = run_echo(*options); });
}

}  // namespace hubrt::hubctl
