// hubctl net-config STATION --host NAME: the Cyclone DDS XML of one host of a station on several
// hosts (no multicast, unicast peers), from the station file (station_network.h). Offline: joins
// no domain. --list prints the hosts, one line each, for scripts (tests/net/run).
#include <fstream>

#include <fmt/format.h>

#include "commands.h"
#include "net_config_xml.h"
#include "session.h"
#include "station_network.h"

namespace hubrt::hubctl {
namespace {

struct NetConfigOptions {
  std::string file;
  std::string host;
  std::string output;
  bool list = false;
};

// "<host> <address> <interface or -> <process>...", one line per host, in file order.
void print_hosts(const StationNetwork& station) {
  for (const StationHost& host : station.hosts) {
    fmt::print("{} {} {}", host.name, host.address, host.interface.empty() ? "-" : host.interface);
    for (const std::string& process : host.runs) fmt::print(" {}", process);
    fmt::print("\n");
  }
}

int run_net_config(const NetConfigOptions& options) {
  auto station = load_station_network(options.file);
  if (!station) {
    fmt::print(stderr, "hubctl net-config: {}\n", station.error().message);
    return kExitUsage;
  }
  if (options.list) {
    print_hosts(*station);
    return kExitOk;
  }
  if (options.host.empty()) {
    fmt::print(stderr, "hubctl net-config: say which host with --host (the station's hosts: {})\n",
               station->host_names());
    return kExitUsage;
  }
  auto xml = cyclone_config_for_host(*station, options.host);
  if (!xml) {
    fmt::print(stderr, "hubctl net-config: {}\n", xml.error().message);
    return kExitUsage;
  }
  if (options.output.empty()) {
    fmt::print("{}", *xml);
    return kExitOk;
  }
  std::ofstream out(options.output);
  out << *xml;
  out.close();
  if (!out) {
    fmt::print(stderr, "hubctl net-config: cannot write {}\n", options.output);
    return kExitFailed;
  }
  return kExitOk;
}

}  // namespace

void add_net_config_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<NetConfigOptions>();
  CLI::App* cmd =
      app.add_subcommand("net-config",
                         "Print the Cyclone DDS configuration of one host of a station on several hosts "
                         "(unicast peers, no multicast), from the station file");
  cmd->footer(
      "The station file says which host runs what (docs/deploy.md, \"A station on several hosts\"). "
      "Exit status: 0 done; 2 the station file, the host or the options are wrong; 1 the output could "
      "not be written.");
  cmd->add_option("station", options->file, "Station file, e.g. tests/net/station-net.yaml")->required();
  cmd->add_option("--host", options->host, "The host to configure (a key of the file's hosts:)");
  cmd->add_option("--output,-o", options->output, "Write the XML to this file instead of stdout");
  cmd->add_flag("--list", options->list, "Print the hosts instead: name, address, interface, processes");
  cmd->callback([options, &exit_code] { exit_code = run_net_config(*options); });
}

}  // namespace hubrt::hubctl
