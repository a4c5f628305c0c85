// hubctl serve: the operator screen — a web page showing who is verified, the planner's current
// instruction, a "done" button and every hub's State (docs/operator-screen.md).
#include "commands.h"
#include "screen_server.h"

namespace hubrt::hubctl {

void add_serve_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ServeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "serve",
      "Serve the operator screen: who is verified, the instruction, a \"done\" button, every hub's State");
  cmd->footer(
      "Read-only for everyone except POST /confirm, which publishes hub_msgs/msg/OperatorConfirm on "
      "--confirm-topic only while an operator is verified (else HTTP 409). Binds to loopback unless "
      "--listen says otherwise. Exit status: 0 stopped; 1 cannot listen; 2 bad arguments or no DDS.");
  cmd->add_option("--listen", options->listen, "ADDR:PORT to listen on (port 0: a free one, printed)")
      ->capture_default_str();
  cmd->add_option("--operator-state", options->operator_state,
                  "The operator panel's State topic (default: the first one found on the domain)");
  cmd->add_option("--confirm-topic", options->confirm_topic, "Where \"done\" presses go")
      ->capture_default_str();
  cmd->add_option("--instruction-topic", options->instruction_topic,
                  "Where the planner publishes hub_msgs/msg/OperatorInstruction")
      ->capture_default_str();
  cmd->add_option("--press-interval", options->min_press_interval_s, "Seconds between two accepted presses")
      ->check(CLI::Range(0.05, 60.0))
      ->capture_default_str();
  cmd->add_option("--duration", options->duration_s, "Stop after this many seconds (default: until Ctrl-C)");
  add_domain_options(*cmd, options->domain);
  cmd->callback([options, &exit_code] { exit_code = run_serve(*options); });
}

}  // namespace hubrt::hubctl
