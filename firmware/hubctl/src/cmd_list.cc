// hubctl list: the hubs on the domain and their topics.
#include <future>
#include <map>
#include <thread>

#include <fmt/format.h>

#include "hubrt/dds/discovery.h"
#include "hubrt/dds/ros_names.h"

#include "commands.h"
#include "hub_diagnostics.h"
#include "peer_authentication.h"
#include "plant_session.h"

namespace hubrt::hubctl {
namespace {

struct ListOptions {
  PlantOptions plant;
  double wait_s = 1.0;
};

// One station's hubs and topics from a discovery snapshot, with the bridged topics /diagnostics
// says are dropping or silent; the lines as printed, indented by `indent`. Errors: discovery failed.
Expected<std::vector<std::string>> station_lines(const dds::Participant& participant,
                                                 const std::map<std::string, BridgeQuiet>& silent,
                                                 const std::string& indent) {
  auto snapshot = dds::discover(participant);
  if (!snapshot) return std::move(snapshot).error();
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
    std::string line = fmt::format("{}  {:6} {:40} {}", indent, writer ? "pub" : "sub",
                                   ros ? *ros : endpoint.topic_name, type ? *type : endpoint.type_name);
    if (const auto quiet = ros ? silent.find(*ros) : silent.end(); writer && quiet != silent.end()) {
      line += fmt::format("  {} ({})", quiet->second.label, quiet->second.message);
    }
    const auto it = names.find(endpoint.participant_key);
    topics_by_participant[it == names.end() ? "(unknown participant)" : it->second].push_back(line);
  }
  std::vector<std::string> out;
  for (auto& [name, lines] : topics_by_participant) {
    std::sort(lines.begin(), lines.end());
    lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
    out.push_back(indent + name);
    out.insert(out.end(), lines.begin(), lines.end());
  }
  return out;
}

int run_list(const ListOptions& options) {
  auto members = join_plant(options.plant, "hubctl");
  if (!members) {
    fmt::print(stderr, "hubctl list: {}\n", members.error().message);
    return kExitUsage;
  }
  // Discovery needs a moment; keep looking for the given time and report what was seen. Meanwhile
  // /diagnostics tells which bridged topics a hubbridge reports dropping or silent: every station's domain
  // listened to at the same time, so a plant takes no longer than one station.
  std::vector<std::future<Expected<std::map<std::string, BridgeQuiet>>>> listening;
  for (const PlantMember& member : *members) {
    listening.push_back(std::async(std::launch::async, [&member, wait_s = options.wait_s] {
      return listen_for_quiet_bridges(member.participant, wait_s);
    }));
  }
  bool any = false;
  int status = kExitOk;
  for (std::size_t k = 0; k < members->size(); ++k) {
    const PlantMember& member = (*members)[k];
    auto silent = listening[k].get();
    auto lines = silent ? station_lines(member.participant, *silent, member.station.empty() ? "" : "  ")
                        : Expected<std::vector<std::string>>(silent.error());
    const std::uint32_t domain = member.participant.domain_id();
    if (!member.station.empty()) fmt::print("station {} (domain {})\n", member.station, domain);
    if (!lines) {
      fmt::print(stderr, "hubctl list: {}{}\n", member.station.empty() ? "" : member.station + ": ",
                 lines.error().message);
      status = kExitFailed;
      continue;
    }
    if (lines->empty()) {
      fmt::print("{}no hubs seen on domain {} within {:.1f} s\n", member.station.empty() ? "" : "  ", domain,
                 options.wait_s);
      if (auto why = authentication_problem(member.participant, options.plant.connection))
        fmt::print("{}\n", *why);
      continue;
    }
    any = true;
    for (const auto& line : *lines) fmt::print("{}\n", line);
  }
  if (status != kExitOk) return status;
  return any ? kExitOk : kExitFailed;
}

}  // namespace

void add_list_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ListOptions>();
  CLI::App* cmd = app.add_subcommand(
      "list",
      "List the hubs on the domain (or on a plant's stations' domains) and the topics they "
      "publish and subscribe");
  add_plant_options(*cmd, options->plant);
  cmd->add_option("--wait", options->wait_s, "Seconds to listen for discovery before listing")
      ->check(CLI::Range(0.0, 60.0));
  cmd->callback([options, &exit_code] { exit_code = run_list(*options); });
}

}  // namespace hubrt::hubctl
