// What every hubctl command shares: joining the domain, finding a topic's type by discovery, and
// stopping on Ctrl-C.
#pragma once

#include <atomic>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "hubrt/base/exit_codes.h"
#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/dds/participant.h"
#include "hubrt/msgs/type_info.h"

namespace hubrt::hubctl {

struct DomainOptions {
  std::optional<std::uint32_t> domain;
  std::string dds_config;
  bool loopback = false;
  double timeout_s = 5.0;    // how long to wait for discovery
  std::string security_dir;  // DDS Security: station folder (hubctl security init) ...
  std::string identity;      // ... and the identity to join as; both or neither
};
// --domain (one id) and add_connection_options().
void add_domain_options(CLI::App& app, DomainOptions& options);
// Everything of add_domain_options but --domain: --dds-config, --loopback, --security,
// --identity, --timeout (the plant-wide tools take --domain as a set: plant_session.h).
void add_connection_options(CLI::App& app, DomainOptions& options);

// --namespace: a station's ROS namespace ("/station1"), checked as a hub file's `namespace:` is
// (config::check_ros_namespace); `description` says what it is for in this command.
void add_namespace_option(CLI::App& app, std::string& ros_namespace, const std::string& description);

// Exit codes shared by all commands: the table of hubrt/base/exit_codes.h, shared with hubd.
inline constexpr int kExitOk = exit_codes::kOk;
inline constexpr int kExitFailed = exit_codes::kFailure;  // the check failed, nothing received, ...
inline constexpr int kExitUsage = exit_codes::kUsage;     // bad arguments, unknown topic or type

// Set by SIGINT/SIGTERM; loops check it.
bool stop_requested() noexcept;
void install_stop_handler();
// The exit status of a command that SIGINT or SIGTERM stopped before it was done (a scenario, a
// wait for readers): 128 + the signal number, as a shell reports a program the signal ended —
// 130 for Ctrl-C, 143 for SIGTERM. Commands that run until stopped (echo, hz, watch, send without
// --once/--count) end normally on the signal and exit 0.
int interrupted_exit_status() noexcept;

Expected<dds::Participant> join_domain(const DomainOptions& options, std::string_view name);

// "/dock/command" for "/dock/command" or "rt/dock/command"; errors for anything else.
Expected<std::string> ros_topic(std::string_view topic);

// The type of `ros_name` as seen on the domain (any writer or reader of it), waiting up to
// `timeout`; or `type_hint` (ROS or DDS type name) when given. Errors: kNotFound naming the topic
// and the topics that do exist with a similar name; kInvalidArgument for an unknown type.
Expected<const msgs::TypeInfo*> topic_type(const dds::Participant& participant, const std::string& ros_name,
                                           const std::string& type_hint, Duration timeout);

Duration seconds(double s);

}  // namespace hubrt::hubctl
