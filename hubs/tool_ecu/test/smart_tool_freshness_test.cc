// The device values in the smart tool's State are current or say "unknown": a controller status
// frame older than its validity (350 ms, the heartbeat's limit; the controller sends one every
// 100 ms) is never shown as the controller's present alarms, program, torque and angle, and an
// input that could not be read this cycle is flagged (inputs_known).
#include <cmath>

#include <gtest/gtest.h>

#include "reading_age.h"
#include "smart_tool_test_support.h"

namespace hubrt::tool_ecu {
namespace {

using namespace testing;  // NOLINT(google-build-using-namespace): the fixture and its helpers

constexpr std::uint32_t kValidityMs = 350;

// The State's controller values are unknown, as the wire contract spells it.
void expect_unknown(const hub_msgs::SmartToolState& state) {
  EXPECT_FALSE(state.status_fresh());
  EXPECT_EQ(state.controller_alarms(), "unknown");
  EXPECT_EQ(state.selected_program(), "unknown");
  EXPECT_TRUE(std::isnan(state.torque_nm())) << "not measured: NaN, not 0 Nm";
  EXPECT_TRUE(std::isnan(state.angle_deg()));
}

TEST_F(SmartToolLogicTest, AStatusOlderThanItsValidityIsUnknownAndFreshOneBringsTheValuesBack) {
  make_ready();
  const Order bolt1 = tighten(1);
  ASSERT_TRUE(tighten_to_the_end(bolt1)) << errors();
  const Order idle = action("idle");
  cycle(&idle);
  ASSERT_TRUE(state_.status_fresh());
  EXPECT_LE(state_.status_age_ms(), 100u);
  EXPECT_EQ(state_.selected_program(), "ladder_frame_bolt");
  EXPECT_EQ(state_.controller_alarms(), "");
  EXPECT_GT(state_.torque_nm(), 5.0F) << "the final torque of the run";

  tool_->power_off();
  bool went_stale = false;
  for (int i = 0; i < 12 && !went_stale; ++i) {  // 600 ms: well past the 350 ms validity
    cycle(&idle);
    // The flag and the age agree on every cycle, and nothing stale is shown as current.
    EXPECT_EQ(state_.status_fresh(), state_.status_age_ms() <= kValidityMs) << state_.status_age_ms();
    went_stale = !state_.status_fresh();
  }
  ASSERT_TRUE(went_stale) << "the status stopped arriving";
  EXPECT_GT(state_.status_age_ms(), kValidityMs);
  EXPECT_LE(state_.status_age_ms(), kValidityMs + 50) << "stale from the first cycle past the validity";
  expect_unknown(state_);
  EXPECT_FALSE(state_.controller_online());
  const std::uint32_t age = state_.status_age_ms();
  cycles(idle, 4);
  EXPECT_EQ(state_.status_age_ms(), age + 200) << "the age keeps growing with the time passed in";
  expect_unknown(state_);

  tool_->power_on();  // it reboots: no program selected, no alarm, torque 0
  ASSERT_TRUE(cycle_until(&idle, [&] { return state_.status_fresh(); }));
  EXPECT_LE(state_.status_age_ms(), kValidityMs);
  EXPECT_EQ(state_.controller_alarms(), "");
  EXPECT_EQ(state_.selected_program(), "") << "the rebooted controller has none";
  EXPECT_EQ(state_.torque_nm(), 0.0F);
}

TEST_F(SmartToolLogicTest, BeforeTheFirstStatusItsAgeSaysNeverAndItsValuesAreUnknown) {
  tool_->power_off();
  logic_.reset();
  auto logic = make_smart_tool_logic(settings_, board_, *fake_, std::make_unique<RspToolHolder>(rsp_),
                                     clock_.now().mono);
  ASSERT_TRUE(logic);
  logic_.emplace(std::move(*logic));
  cycles(nullptr, 3);
  EXPECT_EQ(state_.status_age_ms(), kNeverRead);
  expect_unknown(state_);
  // No run yet: its final torque and angle were never measured either.
  EXPECT_EQ(state_.last_result().program(), "");
  EXPECT_TRUE(std::isnan(state_.last_result().torque_nm()));
  EXPECT_TRUE(std::isnan(state_.last_result().angle_deg()));
}

TEST_F(SmartToolLogicTest, AnInputThatCannotBeReadThisCycleIsFlaggedUnknown) {
  make_ready();
  cycle(nullptr);
  EXPECT_TRUE(state_.inputs_known());
  fake_->input("tool.torque_reached")->set(true);
  cycles(nullptr, 2);  // past the debounce
  ASSERT_TRUE(state_.torque_reached());

  auto wiring = fake_->wiring("tool.torque_reached");
  ASSERT_TRUE(wiring.is_ok());
  ASSERT_TRUE(wiring.value().chip->fail_reads(wiring.value().line, true).is_ok());
  cycle(nullptr);
  EXPECT_FALSE(state_.inputs_known()) << "the same cycle the read failed";
  EXPECT_FALSE(state_.torque_reached()) << "not the last good reading";
  EXPECT_NE(errors().find("input tool.torque_reached failed to read: i/o error"), std::string::npos)
      << errors();

  ASSERT_TRUE(wiring.value().chip->fail_reads(wiring.value().line, false).is_ok());
  cycle(nullptr);
  EXPECT_TRUE(state_.inputs_known());
  cycles(nullptr, 2);  // past the debounce, should the debouncer start over
  EXPECT_TRUE(state_.torque_reached()) << "a good read brings the value back";
}

TEST(ReadingAge, SaturatesInsteadOfWrappingAndNeverGoesNegative) {
  EXPECT_EQ(saturating_age_ms(std::chrono::milliseconds(1234)), 1234u);
  EXPECT_EQ(saturating_age_ms(std::chrono::microseconds(500'300)), 501u) << "rounded up: older than 500 ms";
  EXPECT_EQ(saturating_age_ms(std::chrono::microseconds(499'700)), 500u);
  EXPECT_EQ(saturating_age_ms(Duration::zero()), 0u);
  EXPECT_EQ(saturating_age_ms(-std::chrono::milliseconds(5)), 0u) << "stamped just after the cycle's time";
  EXPECT_EQ(saturating_age_ms(std::chrono::hours(24 * 60)), kNeverRead) << "60 days do not fit";
  EXPECT_EQ(saturating_age_ms(std::chrono::milliseconds(4294967294LL)), 4294967294u);
  const Time t0{std::chrono::seconds(100)};
  EXPECT_EQ(reading_age_ms(false, t0, t0 + std::chrono::seconds(1)), kNeverRead);
  EXPECT_EQ(reading_age_ms(true, t0, t0 + std::chrono::seconds(1)), 1000u);
}

}  // namespace
}  // namespace hubrt::tool_ecu
