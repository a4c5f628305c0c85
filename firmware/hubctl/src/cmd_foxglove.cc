// hubctl foxglove: the station live in Foxglove, over the Foxglove WebSocket protocol
// (docs/foxglove.md). The tap (tap.h) follows the domain's topics; each becomes a channel, its
// samples go to the clients subscribed to it as the CDR bytes that were on the wire. Clients may
// publish commands only with --allow-publish.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>

#include <fmt/format.h>

#include "hubrt/base/utf8.h"

#include "commands.h"
#include "foxglove_bridge.h"
#include "foxglove_commands.h"
#include "foxglove_server.h"
#include "listen_address.h"
#include "session.h"
#include "station_tap.h"

namespace hubrt::hubctl {
namespace {

using Clock = std::chrono::steady_clock;

struct FoxgloveOptions {
  DomainOptions domain;
  std::string listen = "127.0.0.1:8765";
  TapChoice choice;
  bool allow_publish = false;
  std::vector<std::string> publish_origins;
  std::size_t max_clients = 32;
  std::size_t client_queue = 4 * 1024 * 1024;
  double publish_rate = 20;
  std::size_t tap_queue = 100'000;
  double duration_s = 0;
  bool quiet = false;
};

// Every line hubctl foxglove prints about its clients, on stderr, from either thread. A line may
// quote what a client sent (a topic it advertised): escaped as the runtime escapes outside text
// (control characters and bytes that are no UTF-8 as \xHH), so a client cannot drive the terminal
// of whoever reads the log.
void log_line(std::string_view line) {
  std::string shown(line.size() * 4, '\0');  // "\xHH" is the longest a byte becomes
  shown.resize(append_escaped_utf8(line, shown).written);
  std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char stamp[16];
  std::strftime(stamp, sizeof stamp, "%H:%M:%S", &local);
  fmt::print(stderr, "{} foxglove: {}\n", stamp, shown);
  std::fflush(stderr);
}

std::string url(const std::string& address, std::uint16_t port) {
  const bool v6 = address.find(':') != std::string::npos;
  return fmt::format("ws://{}{}{}:{}", v6 ? "[" : "", address, v6 ? "]" : "", port);
}

int run_foxglove(const FoxgloveOptions& options) {
  install_stop_handler();
  auto endpoint = parse_listen(options.listen);
  auto filter = make_tap_filter(options.choice);
  if (!endpoint || !filter) {
    fmt::print(stderr, "hubctl foxglove: {}\n", endpoint ? filter.error().message : endpoint.error().message);
    return kExitUsage;
  }
  auto participant = join_domain(options.domain, "hubctl-foxglove");
  if (!participant) {
    fmt::print(stderr, "hubctl foxglove: {}\n", participant.error().message);
    return kExitUsage;
  }
  std::optional<foxglove::DdsCommandWriters> writers;
  if (options.allow_publish) writers.emplace(*participant, 64);

  foxglove::BridgeOptions bridge_options;
  bridge_options.limits.data_bytes = options.client_queue;
  bridge_options.limits.publish_per_s = options.publish_rate;
  bridge_options.max_clients = options.max_clients;
  bridge_options.allow_publish = options.allow_publish;
  bridge_options.publish_origins = options.publish_origins;
  // Foxglove reads ROS_DISTRO to take the channels as ROS 2 (the "ros2" profile: its Publish panel
  // then writes CDR from the advertised .msg schemas); the station speaks the ROS 2 wire of Humble.
  bridge_options.metadata = {{"ROS_DISTRO", "humble"},
                             {"ROS_DOMAIN_ID", std::to_string(participant->domain_id())}};
  bridge_options.session_id = std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(
                                                 std::chrono::system_clock::now().time_since_epoch())
                                                 .count());
  foxglove::Bridge bridge(bridge_options, writers ? &*writers : nullptr, &log_line);

  TapOptions tap_options;
  tap_options.filter = *filter;
  auto tap = StationTap::start(*participant, std::move(tap_options));
  if (!tap) {
    fmt::print(stderr, "hubctl foxglove: {}\n", tap.error().message);
    return kExitFailed;
  }
  auto source = (*tap)->subscribe(options.tap_queue);

  foxglove::ServerOptions server_options;
  server_options.address = endpoint->address;
  server_options.port = static_cast<std::uint16_t>(endpoint->port);
  auto server = foxglove::WebSocketServer::start(server_options, bridge, &log_line);
  if (!server) {
    fmt::print(stderr, "hubctl foxglove: {}\n", server.error().message);
    return kExitFailed;
  }
  fmt::print("serving {} (Foxglove WebSocket, {}){}\n", url(endpoint->address, (*server)->port()),
             foxglove::kSubprotocol, options.allow_publish ? "; clients may publish commands" : "");
  std::fflush(stdout);

  const auto start = Clock::now();
  auto next_tick = start;
  auto next_progress = start + std::chrono::seconds(10);
  std::uint64_t tap_dropped = 0;
  while (!stop_requested()) {
    const auto now = Clock::now();
    if (options.duration_s > 0 && now - start >= seconds(options.duration_s)) break;
    if (auto event = source->next(std::chrono::milliseconds(100))) bridge.dispatch(*event);
    if (now >= next_tick) {
      next_tick = now + std::chrono::seconds(1);
      bridge.tick(now);
      if (source->dropped() > tap_dropped) {
        log_line(fmt::format("{} samples dropped before reaching any client: hubctl is short of CPU",
                             source->dropped() - tap_dropped));
        tap_dropped = source->dropped();
      }
    }
    if (!options.quiet && now >= next_progress) {
      next_progress = now + std::chrono::seconds(10);
      const auto c = bridge.counters();
      const auto t = (*tap)->counters();
      log_line(fmt::format("{} clients, {} channels, {} samples taken", c.clients, c.channels, t.samples));
    }
  }
  // Clients first (their sessions hold samples), then the tap, then DDS.
  server->reset();
  tap->reset();
  return kExitOk;
}

}  // namespace

void add_foxglove_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<FoxgloveOptions>();
  CLI::App* cmd = app.add_subcommand(
      "foxglove", "Serve the station live to Foxglove (Foxglove WebSocket protocol, foxglove.websocket.v1)");
  cmd->footer(
      "Every State, command, /diagnostics and /sim topic becomes a channel (cdr, ros2msg schema) as its "
      "writers come and go. In Foxglove: Open connection, Foxglove WebSocket, the printed ws:// address; "
      "docs/foxglove-layout.json is a layout for the station (docs/foxglove.md). Clients may publish "
      "commands only with --allow-publish, only on command topics. Exit status: 0 stopped; 1 cannot listen; "
      "2 bad arguments or no DDS.");
  cmd->add_option("--listen", options->listen, "ADDR:PORT to listen on (port 0: a free one, printed)")
      ->capture_default_str();
  cmd->add_option("--topics", options->choice.topics, "Only these topics (ROS names)");
  cmd->add_option("--regex", options->choice.regex, "Only topics whose whole ROS name matches (ECMAScript)");
  cmd->add_flag("--all", options->choice.all, "Every topic of a type this hubctl knows");
  auto* allow =
      cmd->add_flag("--allow-publish", options->allow_publish,
                    "Let clients publish commands (on /<node_type>/command and /<hub>/command only)");
  cmd->add_option("--publish-origin", options->publish_origins,
                  "With --allow-publish: a web origin whose pages may publish, e.g. https://app.foxglove.dev "
                  "(clients that send no Origin, not web pages, may)")
      ->needs(allow);
  cmd->add_option("--publish-rate", options->publish_rate, "Messages a second one client may publish")
      ->check(CLI::Range(0.1, 1000.0))
      ->capture_default_str();
  cmd->add_option("--max-clients", options->max_clients, "Clients connected at once")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000}))
      ->capture_default_str();
  cmd->add_option("--client-queue", options->client_queue,
                  "Bytes of messages held for one client that reads slowly; beyond, its messages are dropped")
      ->transform(CLI::AsSizeValue(false))
      ->check(CLI::Range(std::size_t{1024}, std::size_t{1} << 30))
      ->capture_default_str();
  cmd->add_option("--duration", options->duration_s, "Stop after this many seconds (default: until Ctrl-C)")
      ->check(CLI::Range(0.0, 1e7));
  cmd->add_flag("--quiet,-q", options->quiet, "No progress line every 10 s (client lines stay)");
  add_domain_options(*cmd, options->domain);
  cmd->callback([options, &exit_code] { exit_code = run_foxglove(*options); });
}

}  // namespace hubrt::hubctl
