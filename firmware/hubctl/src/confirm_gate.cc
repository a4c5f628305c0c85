#include "confirm_gate.h"

#include <fmt/format.h>

namespace hubrt::hubctl::screen {

ConfirmDecision ConfirmGate::decide(const ConfirmRequest& request, const OperatorView& op,
                                    std::chrono::steady_clock::time_point now) {
  if (request.marker != kConfirmHeaderValue)
    return {403, "refused: not sent by the operator screen's page", 0};
  if (!request.origin.empty() && request.origin != fmt::format("http://{}", request.host))
    return {403, "refused: another site's page", 0};
  if (op.topic.empty()) return {409, "no operator panel found on the network: the press was not sent", 0};
  if (!op.fresh) return {409, "the operator panel is silent: the press was not sent", 0};
  if (!op.verified) return {409, "no operator is verified: badge in first", 0};
  if (pressed_ && now - last_press_ < min_interval_)
    return {429, "too soon after the last press: wait a moment", 0};
  pressed_ = true;
  last_press_ = now;
  const std::uint32_t id = next_press_id_++;
  return {200, "done: sent", id};
}

}  // namespace hubrt::hubctl::screen
