// hubctl send TOPIC FIELD=VALUE...: publish a command the way the planner does — the same
// wanted state, again and again at a fixed rate, until stopped. With --once or --count the
// samples are not repeated for ever, so each must reach every reader: send waits for the readers
// first (--wait N of them, or until discovery settles) and, before it exits, for every reader to
// acknowledge what it wrote.
#include <chrono>
#include <thread>

#include <fmt/format.h>

#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/json.h"
#include "hubrt/msgs/set_field.h"

#include "command_channel.h"
#include "command_qos.h"
#include "commands.h"
#include "peer_authentication.h"
#include "reader_wait.h"
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
  std::uint32_t wait_readers = 0;  // 0: every reader discovery finds
  bool quiet = false;
  std::uint32_t lifespan_ms = kDefaultCommandLifespanMs;
  double stamp_offset_s = 0.0;  // test aid: source timestamps this far from this host's clock
};

// The source timestamp of a sample written now, `offset_s` away from this host's wall clock.
WallTime stamp_now(double offset_s) {
  const auto now = std::chrono::system_clock::now().time_since_epoch();
  return WallTime{std::chrono::duration_cast<std::chrono::nanoseconds>(now).count() +
                  static_cast<std::int64_t>(offset_s * 1e9)};
}

// Until stopped, a reader that matches late gets the next sample; a limited run must have its
// readers before the first sample goes out, and waits for their acknowledgements at the end.
std::size_t sample_limit(const SendOptions& options) {
  return options.once ? 1 : options.count;
}

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
  auto writer = dds::UntypedWriter::create(*participant, *topic, command_writer_qos(options.lifespan_ms));
  if (!writer) {
    fmt::print(stderr, "hubctl send: {}\n", writer.error().message);
    return kExitFailed;
  }
  const std::size_t limit = sample_limit(options);
  ReaderWait wait;
  wait.wanted = options.wait_readers;
  wait.settle = limit != 0;
  wait.timeout = seconds(options.domain.timeout_s);
  // Matched is not yet heard: a reader that has not heard this writer would drop the sample.
  wait.greet = limit != 0;
  auto readers = wait_for_readers(*writer, wait, *ros_name);
  if (!readers) {
    // Nobody reads because nobody authenticated us (or we them): say so, and send nothing.
    if (auto why = authentication_problem(*participant, options.domain)) {
      fmt::print(stderr, "hubctl send: {}; nothing sent\n", *why);
      return kExitFailed;
    }
    if (limit != 0 || options.wait_readers > 0) {
      fmt::print(stderr, "hubctl send: {}; nothing sent\n", readers.error().message);
      return kExitFailed;
    }
    fmt::print(stderr, "hubctl send: warning: {}; sending anyway\n", readers.error().message);
  } else if (readers->interrupted) {
    fmt::print(stderr, "hubctl send: interrupted while waiting for readers of {}; nothing sent\n", *ros_name);
    return interrupted_exit_status();
  }
  if (!options.quiet)
    fmt::print("sending {} ({}) at {} Hz:\n{}", *ros_name, info.ros_name, options.rate_hz,
               render_human(filled));
  std::fflush(stdout);

  const Duration period = seconds(1.0 / options.rate_hz);
  auto next = std::chrono::steady_clock::now();
  auto last_write = next;
  std::size_t sent = 0;
  // Readers that finish with the sample (echo --count 1) leave before the end: count them now.
  const Result<std::uint32_t> matched = writer->matched_readers();
  while (!stop_requested() && (limit == 0 || sent < limit)) {
    const Status status = options.stamp_offset_s == 0.0
                              ? writer->write(sample.data())
                              : writer->write(sample.data(), stamp_now(options.stamp_offset_s));
    if (!status.is_ok()) {
      fmt::print(stderr, "hubctl send: write failed: {}\n", to_string(status.code()));
      return kExitFailed;
    }
    last_write = std::chrono::steady_clock::now();
    ++sent;
    if (limit != 0 && sent >= limit) break;  // the acknowledgements come next, not another period
    next += period;
    std::this_thread::sleep_until(next);
  }
  if (limit != 0 && sent < limit) {
    fmt::print(stderr, "hubctl send: interrupted after {} of {} sample(s)\n", sent, limit);
    return interrupted_exit_status();
  }
  // The writer goes away with the process, and with it any retransmission a reader still needs.
  if (auto acked = writer->wait_for_acks(seconds(options.domain.timeout_s)); !acked) {
    fmt::print(stderr, "hubctl send: sent {} sample(s) but {}\n", sent, acked.error().message);
    return kExitFailed;
  }
  const auto late = late_acknowledgement(std::chrono::steady_clock::now() - last_write, options.lifespan_ms);
  if (late) fmt::print(stderr, "hubctl send: {}\n", *late);
  if (!options.quiet)
    fmt::print("sent {} sample(s) to {} reader(s); {}\n", sent, matched.is_ok() ? matched.value() : 0,
               late ? "acknowledged past the LIFESPAN" : "all acknowledged");
  return kExitOk;
}

}  // namespace

void add_send_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<SendOptions>();
  CLI::App* cmd =
      app.add_subcommand("send", "Publish a command repeatedly at a fixed rate, as the planner does");
  cmd->footer(
      "Exit status: 0 sent (with --once/--count: and acknowledged by every matched reader); 1 no reader "
      "(with DDS Security: no peer authenticated, said as such), "
      "fewer than --wait N readers, a write failed or a reader did not acknowledge within --timeout; "
      "2 bad arguments, unknown topic or type; 130 (143) Ctrl-C (SIGTERM) before --once/--count was "
      "done. Without --once/--count, Ctrl-C is the normal end (0).");
  cmd->add_option("topic", options->topic, "ROS topic name, e.g. /dock/command")->required();
  cmd->add_option("fields", options->assignments, "FIELD=VALUE, e.g. target_name=dock action=monitor");
  cmd->add_option("--type", options->type, "Message type, when no hub has announced the topic yet");
  cmd->add_option("--rate,-r", options->rate_hz, "Samples per second")->check(CLI::Range(0.01, 10000.0));
  cmd->add_option("--count,-n", options->count,
                  "Stop after this many samples (default: until Ctrl-C); waits for readers and "
                  "acknowledgements as --once does");
  cmd->add_flag("--once", options->once,
                "Send one sample and stop. Waits for readers first: for --wait N of them, else for one "
                "and then until no new reader has matched for 0.5 s (at most --timeout); exits 1 when "
                "none is there. Before exiting, waits (at most --timeout) until every matched reader "
                "acknowledged the sample; exits 1 if one did not");
  cmd->add_option("--wait", options->wait_readers,
                  "Wait until N readers are matched before sending (e.g. one per hub); exit 1 with "
                  "nothing sent if fewer match within --timeout")
      ->check(CLI::Range(1U, 1000U));
  cmd->add_flag("--quiet,-q", options->quiet, "Print nothing but errors");
  add_lifespan_option(*cmd, options->lifespan_ms);
  cmd->add_option("--stamp-offset", options->stamp_offset_s,
                  "Test aid: stamp each sample's DDS source timestamp this many seconds away from this "
                  "host's clock (-10: a planner whose clock is 10 s behind; 10: ahead), to see how a hub "
                  "judges commands' ages (docs/safety.md)")
      ->check(CLI::Range(-86400.0, 86400.0));
  add_domain_options(*cmd, options->domain);
  cmd->callback([options, &exit_code] { exit_code = run_send(*options); });
}

}  // namespace hubrt::hubctl
