// hubctl's commands, each registered on the CLI11 app with its own options.
#pragma once

#include <CLI/CLI.hpp>

namespace hubrt::hubctl {

// Each returns the exit code through `exit_code` when its subcommand ran.
void add_list_command(CLI::App& app, int& exit_code);
void add_echo_command(CLI::App& app, int& exit_code);
void add_send_command(CLI::App& app, int& exit_code);
void add_hz_command(CLI::App& app, int& exit_code);
void add_watch_command(CLI::App& app, int& exit_code);
void add_conformance_command(CLI::App& app, int& exit_code);
void add_play_command(CLI::App& app, int& exit_code);
void add_net_config_command(CLI::App& app, int& exit_code);
void add_security_command(CLI::App& app, int& exit_code);
void add_serve_command(CLI::App& app, int& exit_code);
void add_record_command(CLI::App& app, int& exit_code);
void add_foxglove_command(CLI::App& app, int& exit_code);

}  // namespace hubrt::hubctl
