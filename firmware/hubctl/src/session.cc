#include "session.h"

#include <algorithm>
#include <csignal>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/dds/discovery.h"
#include "hubrt/dds/domain.h"
#include "hubrt/dds/ros_names.h"
#include "hubrt/dds/security_refusals.h"
#include "hubrt/msgs/all_types.h"
#include "hubrt/security/participant_security.h"

namespace hubrt::hubctl {
namespace {

std::atomic<bool> g_stop{false};
std::atomic<int> g_stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "stored from a signal handler");

extern "C" void on_stop_signal(int signal) {
  g_stop_signal.store(signal);
  g_stop.store(true);
}

}  // namespace

void add_domain_options(CLI::App& app, DomainOptions& options) {
  app.add_option("--domain", options.domain, "DDS domain id (default: $ROS_DOMAIN_ID or 0)")
      ->check(CLI::Range(0, 232));
  add_connection_options(app, options);
}

void add_namespace_option(CLI::App& app, std::string& ros_namespace, const std::string& description) {
  app.add_option("--namespace", ros_namespace, description)->check([](const std::string& value) {
    auto valid = config::check_ros_namespace(value);
    return valid ? std::string() : valid.error().message;
  });
}

void add_connection_options(CLI::App& app, DomainOptions& options) {
  app.add_option("--dds-config", options.dds_config,
                 "Cyclone DDS XML configuration (default: $CYCLONEDDS_URI)");
  app.add_flag("--loopback", options.loopback, "Keep DDS on the loopback interface");
  auto* security = app.add_option("--security", options.security_dir,
                                  "DDS Security: the station's security folder (hubctl security init)");
  auto* identity = app.add_option("--identity", options.identity, "DDS Security: the identity to join as");
  security->needs(identity);
  identity->needs(security);
  app.add_option("--timeout", options.timeout_s, "Seconds to wait for the hub to be discovered")
      ->check(CLI::Range(0.0, 3600.0));
}

bool stop_requested() noexcept {
  return g_stop.load();
}

int interrupted_exit_status() noexcept {
  const int signal = g_stop_signal.load();
  return 128 + (signal != 0 ? signal : SIGINT);
}

void install_stop_handler() {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
}

Duration seconds(double s) {
  return std::chrono::nanoseconds(static_cast<std::int64_t>(s * 1e9));
}

Expected<dds::Participant> join_domain(const DomainOptions& options, std::string_view name) {
  auto config = dds::domain_config_from_environment();
  if (!config) return std::move(config).error();
  if (options.domain) config->domain_id = *options.domain;
  if (options.loopback) config->cyclone_xml = dds::loopback_config_xml();
  if (!options.dds_config.empty()) config->cyclone_xml = options.dds_config;
  if (!options.security_dir.empty()) {
    // Before the participant: refused handshakes are counted (and logged rate-limited) from the
    // start, so that a command finding nobody can say authentication failed (peer_authentication.h).
    dds::count_security_refusals();
    const auto now = std::chrono::system_clock::now().time_since_epoch();
    auto secured = security::security_xml_for({options.security_dir, options.identity},
                                              std::chrono::duration_cast<std::chrono::seconds>(now).count());
    if (!secured) return std::move(secured).error();
    config->cyclone_xml = security::with_security(config->cyclone_xml, *secured);
  }
  auto participant = dds::Participant::create(*config, name);
  if (!participant && !options.security_dir.empty()) {
    // The credentials passed our own check: Cyclone's security plugins said why on stderr.
    return make_error(participant.error().code, participant.error().message +
                                                    "; with DDS Security identity '" + options.identity +
                                                    "' (Cyclone's reason is logged above)");
  }
  return participant;
}

Expected<std::string> ros_topic(std::string_view topic) {
  std::string name(topic);
  if (name.rfind("rt/", 0) == 0) name = name.substr(2);
  if (auto ok = dds::validate_ros_topic_name(name); !ok) return std::move(ok).error();
  return name;
}

Expected<const msgs::TypeInfo*> topic_type(const dds::Participant& participant, const std::string& ros_name,
                                           const std::string& type_hint, Duration timeout) {
  const msgs::TypeRegistry& types = msgs::all_types();
  if (!type_hint.empty()) {
    const msgs::TypeInfo* type = types.find(type_hint);
    if (type == nullptr) {
      return make_error(ErrorCode::kInvalidArgument, types.unknown_type_message(type_hint));
    }
    return type;
  }
  auto dds_topic = dds::ros_to_dds_topic(ros_name);
  if (!dds_topic) return std::move(dds_topic).error();
  const std::string& dds_name = *dds_topic;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::vector<std::string> seen;
  for (;;) {
    auto snapshot = dds::discover(participant);
    if (!snapshot) return std::move(snapshot).error();
    seen.clear();
    for (const dds::TopicSummary& topic : snapshot->topics()) {
      if (topic.topic_name == dds_name &&
          (topic.writers > topic.local_writers || topic.readers > topic.local_readers)) {
        const msgs::TypeInfo* type = types.find_by_dds_name(topic.type_name);
        if (type == nullptr) {
          return make_error(ErrorCode::kInvalidArgument,
                            fmt::format("{} carries type '{}', which this hubctl does not know", ros_name,
                                        topic.type_name));
        }
        return type;
      }
      if (topic.topic_name.rfind("rt/", 0) == 0) seen.push_back(topic.topic_name.substr(2));
    }
    if (std::chrono::steady_clock::now() >= deadline || stop_requested()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  return make_error(
      ErrorCode::kNotFound,
      fmt::format("nobody publishes or subscribes {} on this domain (waited {:.1f} s); topics seen: {}",
                  ros_name, to_seconds(timeout),
                  seen.empty() ? "none" : fmt::format("{}", fmt::join(seen, ", "))));
}

}  // namespace hubrt::hubctl
