#include "hubrt/hal/fake/tightening_run.h"

#include <gtest/gtest.h>

namespace hubrt::hal::fake {
namespace {

namespace st = protocol::smart_tool;
using std::chrono::milliseconds;

constexpr Time kStart{std::chrono::hours(1)};
// 20 Nm/s and 360 °/s: 10 Nm is reached after 0.5 s at 180.0°.
constexpr RunPhysics kPhysics{20.0, 360.0, std::chrono::seconds(5), 0.3};

TEST(TighteningRun, TorqueRampsAtTheRateAndStopsAtTheTarget) {
  const auto run = TighteningRun::forward(st::Program{1, 1000, 1500, 2000}, kPhysics, false, kStart);
  EXPECT_EQ(run.natural_end(), kStart + milliseconds(500));
  EXPECT_EQ(run.natural_cause(), RunEnd::kTorqueReached);
  EXPECT_EQ(run.torque_cnm(kStart), 0);
  EXPECT_EQ(run.torque_cnm(kStart + milliseconds(100)), 200);
  EXPECT_EQ(run.angle_ddeg(kStart + milliseconds(100)), 360);
  EXPECT_EQ(run.torque_cnm(kStart + milliseconds(250)), 500);
  EXPECT_EQ(run.torque_cnm(kStart + milliseconds(500)), 1000);
  EXPECT_EQ(run.angle_ddeg(kStart + milliseconds(500)), 1800);
  EXPECT_EQ(run.torque_cnm(kStart + milliseconds(900)), 1000) << "values freeze at the end of the run";
  EXPECT_EQ(run.angle_ddeg(kStart + milliseconds(900)), 1800);

  const st::RunResult r = run.result(run.natural_end(), RunEnd::kTorqueReached, 4);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.nok_reasons, 0);
  EXPECT_EQ(r.program, 1);
  EXPECT_EQ(r.run_counter, 4);
}

TEST(TighteningRun, AngleBelowTheWindowAtTargetTorqueIsNok) {
  const auto run = TighteningRun::forward(st::Program{1, 1000, 2000, 3000}, kPhysics, false, kStart);
  EXPECT_EQ(run.natural_cause(), RunEnd::kTorqueReached);
  const st::RunResult r = run.result(run.natural_end(), run.natural_cause(), 1);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.nok_reasons, st::nok_reason::kAngleLow);
  EXPECT_EQ(r.torque_cnm, 1000);
}

TEST(TighteningRun, AnglePastTheWindowAbortsAtMaxPlusOneStep) {
  const auto run = TighteningRun::forward(st::Program{1, 1000, 100, 1000}, kPhysics, false, kStart);
  EXPECT_EQ(run.natural_cause(), RunEnd::kAngleHigh);
  const st::RunResult r = run.result(run.natural_end(), run.natural_cause(), 1);
  EXPECT_EQ(r.angle_ddeg, 1001);
  EXPECT_EQ(run.angle_ddeg(run.natural_end() - Duration(1)), 1000)
      << "one nanosecond earlier it was in the window";
  EXPECT_EQ(r.nok_reasons, st::nok_reason::kAngleHigh | st::nok_reason::kTorqueLow);
  EXPECT_LT(r.torque_cnm, 1000);
}

TEST(TighteningRun, SlipStallsTorqueAndEndsByAngleOrTimeout) {
  const auto by_angle = TighteningRun::forward(st::Program{1, 1000, 0, 3000}, kPhysics, true, kStart);
  EXPECT_EQ(by_angle.natural_cause(), RunEnd::kAngleHigh);
  EXPECT_EQ(by_angle.torque_cnm(by_angle.natural_end()), 300);

  const auto by_time = TighteningRun::forward(st::Program{1, 1000, 0, 65000}, kPhysics, true, kStart);
  EXPECT_EQ(by_time.natural_cause(), RunEnd::kTimeout);
  EXPECT_EQ(by_time.natural_end(), kStart + std::chrono::seconds(5));
  const st::RunResult r = by_time.result(by_time.natural_end(), RunEnd::kTimeout, 1);
  EXPECT_EQ(r.nok_reasons, st::nok_reason::kRunTimeout | st::nok_reason::kTorqueLow);
}

TEST(TighteningRun, InterruptedRunsNameTheirCause) {
  const auto run = TighteningRun::forward(st::Program{1, 1000, 0, 3000}, kPhysics, false, kStart);
  const Time t = kStart + milliseconds(200);
  EXPECT_EQ(run.result(t, RunEnd::kStopped, 1).nok_reasons,
            st::nok_reason::kStoppedByCommand | st::nok_reason::kTorqueLow);
  EXPECT_EQ(run.result(t, RunEnd::kAlarm, 1).nok_reasons,
            st::nok_reason::kAlarm | st::nok_reason::kTorqueLow);
  EXPECT_EQ(run.result(t, RunEnd::kLinkLost, 1).nok_reasons,
            st::nok_reason::kLinkLost | st::nok_reason::kTorqueLow);
  EXPECT_EQ(run.result(t, RunEnd::kStopped, 1).torque_cnm, 400);
}

TEST(TighteningRun, ReverseRunTurnsWithoutTorqueUntilStopped) {
  const auto run = TighteningRun::reverse(kPhysics, kStart);
  EXPECT_TRUE(run.is_reverse());
  EXPECT_EQ(run.natural_end(), Time::max());
  EXPECT_EQ(run.angle_ddeg(kStart + std::chrono::seconds(1)), 3600);
  EXPECT_EQ(run.torque_cnm(kStart + std::chrono::seconds(1)), 0);
}

}  // namespace
}  // namespace hubrt::hal::fake
