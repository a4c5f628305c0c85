// The one thing the operator screen changes: a "done" press, POST /confirm. Decides, without
// I/O and with the time passed in, whether a request may become an OperatorConfirm sample:
//   - it comes from the screen's own page: the header `X-Hubrt-Screen: confirm`, which a page of
//     another origin cannot send without a CORS preflight this server never grants, and an
//     Origin header (when the browser sends one) equal to http://<Host>;
//   - an operator is verified now (their panel's State is fresh and says so); the hub checks it
//     again, this only spares the operator a press that would count for nothing;
//   - at most one press per `min_interval` (a bouncing finger or a script is not many presses).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

#include "listen_address.h"
#include "screen_format.h"

namespace hubrt::hubctl::screen {

inline constexpr std::string_view kConfirmHeader = "X-Hubrt-Screen";
inline constexpr std::string_view kConfirmHeaderValue = "confirm";

struct ConfirmRequest {
  std::string_view marker;  // the X-Hubrt-Screen header ("" when absent)
  std::string_view origin;  // the Origin header ("" when absent)
  std::string_view host;    // the Host header
};

struct ConfirmDecision {
  int http_status = 0;         // 200 accepted, 403 not from the page, 409 nobody verified, 429 too soon
  std::string message;         // for the page (plain text; the page shows it with textContent)
  std::uint32_t press_id = 0;  // the sample's press_id when accepted
};

class ConfirmGate {
 public:
  // `first_press_id`: the first press's id (random per server: the hub ignores a press_id equal
  // to the last one it took, which a restarted server counting from 1 could repeat).
  ConfirmGate(std::uint32_t first_press_id, std::chrono::milliseconds min_interval)
      : next_press_id_(first_press_id), min_interval_(min_interval) {}

  // Accepting consumes a press_id and starts the interval.
  ConfirmDecision decide(const ConfirmRequest& request, const OperatorView& op,
                         std::chrono::steady_clock::time_point now);

 private:
  std::uint32_t next_press_id_;
  std::chrono::milliseconds min_interval_;
  bool pressed_ = false;
  std::chrono::steady_clock::time_point last_press_{};
};

// The Host headers the screen answers (listen_address.h).
using hubctl::host_allowed;

}  // namespace hubrt::hubctl::screen
