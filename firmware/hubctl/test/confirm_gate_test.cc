// The confirm rules of the operator screen: only the page's own request, only while a verified
// operator's panel is fresh, at most one press per interval, a new press_id each time.
#include "confirm_gate.h"

#include <gtest/gtest.h>

namespace hubrt::hubctl::screen {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

OperatorView verified() {
  OperatorView op;
  op.topic = "/operator_hub/panel/state";
  op.fresh = true;
  op.verified = true;
  op.name = "Anna Svensson";
  return op;
}

constexpr ConfirmRequest kFromPage{"confirm", "http://127.0.0.1:8080", "127.0.0.1:8080"};

TEST(ConfirmGate, AcceptsThePagesPressWithNewIds) {
  ConfirmGate gate(41, milliseconds(1000));
  const auto t0 = Clock::time_point{} + std::chrono::hours(1);
  auto first = gate.decide(kFromPage, verified(), t0);
  EXPECT_EQ(first.http_status, 200);
  EXPECT_EQ(first.press_id, 41U);
  auto second = gate.decide({"confirm", "", "127.0.0.1:8080"}, verified(), t0 + milliseconds(1000));
  EXPECT_EQ(second.http_status, 200);  // no Origin (same-origin requests may omit it)
  EXPECT_EQ(second.press_id, 42U);
}

TEST(ConfirmGate, RefusesWithoutAVerifiedFreshOperator) {
  ConfirmGate gate(1, milliseconds(1000));
  const auto now = Clock::time_point{} + std::chrono::hours(1);
  OperatorView none = verified();
  none.verified = false;
  EXPECT_EQ(gate.decide(kFromPage, none, now).http_status, 409);
  OperatorView silent = verified();
  silent.fresh = false;
  EXPECT_EQ(gate.decide(kFromPage, silent, now).http_status, 409);
  EXPECT_EQ(gate.decide(kFromPage, OperatorView{}, now).http_status, 409);
  // Refusals use no press_id and start no interval.
  const auto ok = gate.decide(kFromPage, verified(), now);
  EXPECT_EQ(ok.http_status, 200);
  EXPECT_EQ(ok.press_id, 1U);
}

TEST(ConfirmGate, RefusesOtherOriginsAndRequestsWithoutTheHeader) {
  ConfirmGate gate(1, milliseconds(1000));
  const auto now = Clock::time_point{} + std::chrono::hours(1);
  EXPECT_EQ(gate.decide({"", "", "127.0.0.1:8080"}, verified(), now).http_status, 403);
  EXPECT_EQ(gate.decide({"Confirm ", "", "127.0.0.1:8080"}, verified(), now).http_status, 403);
  EXPECT_EQ(gate.decide({"confirm", "http://evil.example", "127.0.0.1:8080"}, verified(), now).http_status,
            403);
  EXPECT_EQ(gate.decide({"confirm", "null", "127.0.0.1:8080"}, verified(), now).http_status, 403);
}

TEST(ConfirmGate, RateLimitsPresses) {
  ConfirmGate gate(7, milliseconds(1000));
  const auto t0 = Clock::time_point{} + std::chrono::hours(1);
  EXPECT_EQ(gate.decide(kFromPage, verified(), t0).http_status, 200);
  const auto soon = gate.decide(kFromPage, verified(), t0 + milliseconds(999));
  EXPECT_EQ(soon.http_status, 429);
  EXPECT_EQ(soon.press_id, 0U);
  const auto later = gate.decide(kFromPage, verified(), t0 + milliseconds(1000));
  EXPECT_EQ(later.http_status, 200);
  EXPECT_EQ(later.press_id, 8U);
}

TEST(ConfirmGate, HostCheckOnLoopback) {
  EXPECT_TRUE(host_allowed("127.0.0.1:8080", "127.0.0.1", 8080));
  EXPECT_TRUE(host_allowed("localhost:8080", "127.0.0.1", 8080));
  EXPECT_FALSE(host_allowed("evil.example:8080", "127.0.0.1", 8080));  // DNS rebinding
  EXPECT_FALSE(host_allowed("127.0.0.1:9090", "127.0.0.1", 8080));
  EXPECT_FALSE(host_allowed("", "127.0.0.1", 8080));
  EXPECT_TRUE(host_allowed("station-7:8080", "0.0.0.0", 8080));
  EXPECT_FALSE(host_allowed("", "0.0.0.0", 8080));
}

}  // namespace
}  // namespace hubrt::hubctl::screen
