// hubctl send TOPIC FIELD=VALUE...: publish a command the way the planner does — the same
// wanted state, again and again at a fixed rate, until stopped.
#include <thread>

#include <fmt/format.h>

#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/json.h"
#include "hubrt/msgs/set_field.h"

#include "commands.h"
#include "render.h"
#include "session.h"

namespace hubrt::hubctl {
namespace {

struct SendOptions {
  DomainOptions domain;
  std::string topic;
  std::vector<std::string> assignments;
  std::string type;
  double rate_hz = 10.0;
  std::size_t count = 0;  // 0 = until stopped
  bool once = false;
  bool quiet = false;
};

int run_send(const SendOptions& options) {
  install_stop_handler();
  auto ros_name = ros_topic(options.topic);
  if (!ros_name) {
    fmt::print(stderr, "hubctl send: {}\n", ros_name.error().message);
    return kExitUsage;
  }
  auto participant = join_domain(options.domain, "hubctl");
  if (!participant) {
    fmt::print(stderr, "hubctl send: {}\n", participant.error().message);
    return kExitUsage;
  }
  auto type = topic_type(*participant, *ros_name, options.type, seconds(options.domain.timeout_s));
  if (!type) {
    fmt::print(stderr, "hubctl send: {}\n", type.error().message);
    return kExitUsage;
  }
  const msgs::TypeInfo& info = **type;
  dds::UntypedSample sample(*info.descriptor);
  for (const std::string& assignment : options.assignments) {
    const auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0) {
      fmt::print(stderr, "hubctl send: '{}' is not FIELD=VALUE\n", assignment);
      return kExitUsage;
    }
    auto set = msgs::set_field(info, sample.data(), std::string_view(assignment).substr(0, eq),
                               std::string_view(assignment).substr(eq + 1));
    if (!set) {
      fmt::print(stderr, "hubctl send: {}\n", set.error().message);
      return kExitUsage;
    }
  }
  // Unset strings go on the wire as "", not as a null the serializer refuses.
  const auto filled = msgs::to_json(info, sample.data());
  if (auto ok = msgs::from_json(info, filled, sample.data()); !ok) {
    fmt::print(stderr, "hubctl send: {}\n", ok.error().message);
    return kExitFailed;
  }
  auto topic = dds::UntypedTopic::create(*participant, *info.descriptor, *ros_name);
  if (!topic) {
    fmt::print(stderr, "hubctl send: {}\n", topic.error().message);
    return kExitFailed;
  }
  auto writer = dds::UntypedWriter::create(*participant, *topic);
  if (!writer) {
    fmt::print(stderr, "hubctl send: {}\n", writer.error().message);
    return kExitFailed;
  }
  if (auto matched = writer->wait_for_readers(1, seconds(options.domain.timeout_s)); !matched) {
    fmt::print(stderr, "hubctl send: warning: {}; sending anyway\n", matched.error().message);
  }
  if (!options.quiet)
    fmt::print("sending {} ({}) at {} Hz:\n{}", *ros_name, info.ros_name, options.rate_hz,
               render_human(filled));
  std::fflush(stdout);

  const std::size_t limit = options.once ? 1 : options.count;
  const Duration period = seconds(1.0 / options.rate_hz);
  auto next = std::chrono::steady_clock::now();
  std::size_t sent = 0;
  while (!stop_requested() && (limit == 0 || sent < limit)) {
    if (auto status = writer->write(sample.data()); !status.is_ok()) {
      fmt::print(stderr, "hubctl send: write failed: {}\n", to_string(status.code()));
      return kExitFailed;
    }
    ++sent;
    next += period;
    std::this_thread::sleep_until(next);
  }
  if (!options.quiet) fmt::print("sent {} sample(s)\n", sent);
  // Give reliable delivery a moment before the writer goes away with the process.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  return kExitOk;
}

}  // namespace

void add_send_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<SendOptions>();
  CLI::App* cmd =
      app.add_subcommand("send", "Publish a command repeatedly at a fixed rate, as the planner does");
  cmd->add_option("topic", options->topic, "ROS topic name, e.g. /dock/command")->required();
  cmd->add_option("fields", options->assignments, "FIELD=VALUE, e.g. target_name=dock action=monitor");
  cmd->add_option("--type", options->type, "Message type, when no hub has announced the topic yet");
  cmd->add_option("--rate,-r", options->rate_hz, "Samples per second")->check(CLI::Range(0.01, 10000.0));
  cmd->add_option("--count,-n", options->count, "Stop after this many samples (default: until Ctrl-C)");
  cmd->add_flag("--once", options->once, "Send one sample and stop");
  cmd->add_flag("--quiet,-q", options->quiet, "Print nothing but errors");
  add_domain_options(*cmd, options->domain);
  cmd->callback([options, &exit_code] { exit_code = run_send(*options); });
}

}  // namespace hubrt::hubctl
