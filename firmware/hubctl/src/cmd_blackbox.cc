// hubctl blackbox HUB: ask a running hub to write its black box now (the last minute of its
// commands, States and /diagnostics, as MCAP in its black box directory) and say where it went.
// The request and the answer are diagnostic_msgs/KeyValue on <ns>/<hub>/blackbox/request and
// /written (firmware/assembly black_box_service.h); the hub writes at most one file per 10 s.
#include <unistd.h>

#include <random>
#include <thread>

#include <fmt/format.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"

#include "commands.h"
#include "diagnostic_msgs_typed.h"
#include "reader_wait.h"
#include "session.h"

namespace hubrt::hubctl {
namespace {

using KeyValue = diagnostic_msgs_msg_dds__KeyValue_;

struct BlackBoxOptions {
  DomainOptions domain;
  std::string hub;
  std::string ros_namespace;
};

// How long an unanswered request waits before it is sent again.
constexpr auto kAskAgainAfter = std::chrono::seconds(2);

std::string random_id() {
  std::random_device device;
  return fmt::format("{:08x}{:08x}", device(), device());
}

int run_blackbox(const BlackBoxOptions& options) {
  install_stop_handler();
  const std::string prefix = fmt::format("{}/{}/blackbox", options.ros_namespace, options.hub);
  auto request_topic_name = ros_topic(prefix + "/request");
  if (!request_topic_name) {
    fmt::print(stderr, "hubctl blackbox: {}\n", request_topic_name.error().message);
    return kExitUsage;
  }
  auto participant = join_domain(options.domain, "hubctl");
  if (!participant) {
    fmt::print(stderr, "hubctl blackbox: {}\n", participant.error().message);
    return kExitUsage;
  }
  auto request_topic = dds::Topic<KeyValue>::create(*participant, *request_topic_name);
  auto reply_topic = dds::Topic<KeyValue>::create(*participant, prefix + "/written");
  if (!request_topic || !reply_topic) {
    fmt::print(stderr, "hubctl blackbox: {}\n",
               (!request_topic ? request_topic.error() : reply_topic.error()).message);
    return kExitFailed;
  }
  auto reader = dds::Reader<KeyValue>::create(*participant, *reply_topic, dds::Qos::ros2_default(100));
  auto writer =
      dds::Writer<KeyValue>::create(*participant, *request_topic, announceable(dds::Qos::ros2_default()));
  if (!reader || !writer) {
    fmt::print(stderr, "hubctl blackbox: {}\n", (!reader ? reader.error() : writer.error()).message);
    return kExitFailed;
  }
  // The hub's request reader and our reply reader must be matched before the request goes out:
  // neither writer keeps a sample for a reader that comes later (volatile).
  ReaderWait wait;
  wait.wanted = 1;
  wait.timeout = seconds(options.domain.timeout_s);
  wait.greet = true;  // the request goes once: the hub's reader must have heard this writer
  auto readers = wait_for_readers(writer->untyped(), wait, *request_topic_name);
  if (!readers || readers->interrupted) {
    fmt::print(stderr, "hubctl blackbox: {}\n",
               readers ? "interrupted"
                       : fmt::format("is hub '{}' running? {}", options.hub, readers.error().message));
    return readers ? interrupted_exit_status() : kExitFailed;
  }
  if (auto matched = reader->wait_for_writers(1, seconds(options.domain.timeout_s)); !matched) {
    fmt::print(stderr, "hubctl blackbox: hub '{}' has no black box answer topic: {}\n", options.hub,
               matched.error().message);
    return kExitFailed;
  }
  const std::string id = random_id();
  char host[256] = {};
  (void)gethostname(host, sizeof host - 1);
  dds::Sample<KeyValue> request;
  request->key = dds_string_dup(id.c_str());
  request->value = dds_string_dup(fmt::format("hubctl blackbox on {}", host).c_str());
  // Writing a minute of a busy hub takes a moment; generous for a loaded Pi.
  const auto deadline = std::chrono::steady_clock::now() + seconds(std::max(options.domain.timeout_s, 30.0));
  // The hub answers once, from its long-lived writer: an answer written before that writer has
  // matched our reader, or before our reader has heard it, is lost (docs/interop.md, "A sample
  // written once"). So the request goes again, with the same id, until an answer comes: the hub
  // answers a repeated id with the answer it gave (one file, never "busy" for our own request).
  auto next_send = std::chrono::steady_clock::now();
  dds::Sample<KeyValue> reply;
  while (!stop_requested() && std::chrono::steady_clock::now() < deadline) {
    if (std::chrono::steady_clock::now() >= next_send) {
      if (auto status = writer->write(*request); !status.is_ok()) {
        fmt::print(stderr, "hubctl blackbox: sending the request failed: {}\n", to_string(status.code()));
        return kExitFailed;
      }
      next_send = std::chrono::steady_clock::now() + kAskAgainAfter;
    }
    const Result<bool> taken = reader->take_next(reply);
    if (!taken.is_ok() || !taken.value()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    if (reply->key == nullptr || id != reply->key) continue;  // someone else's answer
    const std::string answer = reply->value != nullptr ? reply->value : "";
    if (answer.rfind("written ", 0) == 0) {
      fmt::print("{}: black box {}\n", options.hub, answer);
      return kExitOk;
    }
    fmt::print(stderr, "hubctl blackbox: {}: {}\n", options.hub, answer);
    return kExitFailed;
  }
  if (stop_requested()) return interrupted_exit_status();
  fmt::print(stderr, "hubctl blackbox: no answer from '{}'\n", options.hub);
  return kExitFailed;
}

}  // namespace

void add_blackbox_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<BlackBoxOptions>();
  CLI::App* cmd =
      app.add_subcommand("blackbox", "Ask a hub to write its black box now and say where it went");
  cmd->footer(
      "The hub writes the last minute (its hub file's blackbox.seconds) of its commands, States and "
      "/diagnostics as MCAP into its black box directory (/var/lib/hubrt/blackbox on a board): read it "
      "with hubctl echo/watch --from, or Foxglove. At most one file per 10 s on request. Exit status: 0 "
      "written; 1 no hub, no answer or the hub could not write it; 2 bad arguments.");
  cmd->add_option("hub", options->hub, "The hub's name, e.g. dock_ecu")->required();
  add_namespace_option(*cmd, options->ros_namespace, "The station's ROS namespace, e.g. /station1");
  add_domain_options(*cmd, options->domain);
  cmd->callback([options, &exit_code] { exit_code = run_blackbox(*options); });
}

}  // namespace hubrt::hubctl
