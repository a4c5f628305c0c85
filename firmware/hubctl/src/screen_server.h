// hubctl serve: the operator screen's HTTP server (cpp-httplib). One DDS thread discovers every
// hub State (StationWatch), reads the planner's instruction and publishes the "done" presses; the
// HTTP threads read its last snapshot under a mutex. Read-only except POST /confirm.
//   GET /            the page (web/index.html with the first view rendered in)
//   GET /screen.js, /screen.css
//   GET /state       the snapshot as JSON
//   GET /events      server-sent events: "state" with the snapshot whenever it changes
//   POST /confirm    a "done" press (ConfirmGate's rules)
#pragma once

#include <cstdint>
#include <string>

#include "session.h"

namespace hubrt::hubctl {

struct ServeOptions {
  DomainOptions domain;
  std::string listen = "127.0.0.1:8080";  // ADDR:PORT; port 0 picks a free one
  std::string operator_state;             // "" = the first operator panel State found
  std::string confirm_topic = "/operator_hub/operator/screen_confirm";
  std::string instruction_topic = "/operator/instruction";
  double min_press_interval_s = 1.0;
  double duration_s = 0;  // 0 = until stopped
};

// Runs until SIGINT/SIGTERM (or duration); prints "serving http://ADDR:PORT/" once listening.
int run_serve(const ServeOptions& options);

}  // namespace hubrt::hubctl
