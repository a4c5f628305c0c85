// hubctl — talk to hubs from any machine on the network: list them, watch their State, command
// them the way the planner does, measure their heartbeat.
#include <CLI/CLI.hpp>

#include "commands.h"
#include "session.h"

int main(int argc, char** argv) {
  CLI::App app{"hubctl — list, watch, command and measure hubs over DDS"};
  app.require_subcommand(1);
  app.footer(hubrt::exit_codes::kHelpFooter);
  int exit_code = hubrt::hubctl::kExitOk;
  hubrt::hubctl::add_list_command(app, exit_code);
  hubrt::hubctl::add_echo_command(app, exit_code);
  hubrt::hubctl::add_send_command(app, exit_code);
  hubrt::hubctl::add_hz_command(app, exit_code);
  hubrt::hubctl::add_watch_command(app, exit_code);
  hubrt::hubctl::add_conformance_command(app, exit_code);
  hubrt::hubctl::add_play_command(app, exit_code);
  hubrt::hubctl::add_record_command(app, exit_code);
  hubrt::hubctl::add_net_config_command(app, exit_code);
  hubrt::hubctl::add_security_command(app, exit_code);
  hubrt::hubctl::add_serve_command(app, exit_code);
  hubrt::hubctl::add_foxglove_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11's own codes (105, 106, 109...) all mean "bad command line": the table's 2.
    const int code = app.exit(e);
    return code == 0 ? 0 : hubrt::hubctl::kExitUsage;
  }
  return exit_code;
}
