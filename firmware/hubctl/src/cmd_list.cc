// hubctl list: the hubs on the domain and their topics.
#include <map>
#include <thread>

#include <fmt/format.h>

#include "hubrt/dds/discovery.h"
#include "hubrt/dds/ros_names.h"

#include "commands.h"
#include "hub_diagnostics.h"
#include "peer_authentication.h"
#include "session.h"

namespace hubrt::hubctl {
namespace {

struct ListOptions {
  DomainOptions domain;
  double wait_s = 1.0;
};

int run_list(const ListOptions& options) {
  auto participant = join_domain(options.domain, "hubctl");
  if (!participant) {
    fmt::print(stderr, "hubctl list: {}\n", participant.error().message);
    return kExitUsage;
  }
  // Discovery needs a moment; keep looking for the given time and report what was seen. Meanwhile
  // /diagnostics tells which bridged topics a hubbridge reports dropping or silent.
  auto silent = listen_for_quiet_bridges(*participant, options.wait_s);
  if (!silent) {
    fmt::print(stderr, "hubctl list: {}\n", silent.error().message);
    return kExitFailed;
  }
  auto snapshot = dds::discover(*participant);
  if (!snapshot) {
    fmt::print(stderr, "hubctl list: {}\n", snapshot.error().message);
    return kExitFailed;
  }
  std::map<dds::Guid, std::string> names;
  for (const auto& p : snapshot->participants) {
    if (!p.local) names[p.key] = p.name.empty() ? "(unnamed)" : p.name;
  }
  // A hub is a participant that writes at least one State topic.
  std::map<std::string, std::vector<std::string>> topics_by_participant;
  for (const auto& endpoint : snapshot->endpoints) {
    if (endpoint.local) continue;
    const auto ros = dds::dds_to_ros_topic(endpoint.topic_name);
    auto type = dds::dds_to_ros_type(endpoint.type_name);
    const bool writer = endpoint.direction == dds::EndpointDirection::kWriter;
    std::string line = fmt::format("  {:6} {:40} {}", writer ? "pub" : "sub",
                                   ros ? *ros : endpoint.topic_name, type ? *type : endpoint.type_name);
    if (const auto quiet = ros ? silent->find(*ros) : silent->end(); writer && quiet != silent->end()) {
      line += fmt::format("  {} ({})", quiet->second.label, quiet->second.message);
    }
    const auto it = names.find(endpoint.participant_key);
    topics_by_participant[it == names.end() ? "(unknown participant)" : it->second].push_back(line);
  }
  if (topics_by_participant.empty()) {
    fmt::print("no hubs seen on domain {} within {:.1f} s\n", participant->domain_id(), options.wait_s);
    if (auto why = authentication_problem(*participant, options.domain)) fmt::print("{}\n", *why);
    return kExitFailed;
  }
  for (auto& [name, lines] : topics_by_participant) {
    std::sort(lines.begin(), lines.end());
    lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
    fmt::print("{}\n", name);
    for (const auto& line : lines) fmt::print("{}\n", line);
  }
  return kExitOk;
}

}  // namespace

void add_list_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ListOptions>();
  CLI::App* cmd =
      app.add_subcommand("list", "List the hubs on the domain and the topics they publish and subscribe");
  add_domain_options(*cmd, options->domain);
  cmd->add_option("--wait", options->wait_s, "Seconds to listen for discovery before listing")
      ->check(CLI::Range(0.0, 60.0));
  cmd->callback([options, &exit_code] { exit_code = run_list(*options); });
}

}  // namespace hubrt::hubctl
