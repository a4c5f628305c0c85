#include "hubrt/hal/fake/pressure_supply.h"

#include <gmock/gmock.h>

#include "sim_test_support.h"

namespace hubrt::hal::fake {
namespace {

using std::chrono::milliseconds;
using ::testing::ElementsAre;

class PressureSupplyTest : public SimTest {};

TEST_F(PressureSupplyTest, SwitchFollowsDropAndRestoreAtOnce) {
  const Time t0 = now();
  auto& supply = gpio_.add_simulator(std::make_unique<PressureSupply>(gpio_, line(5), /*ok_initially=*/true));
  auto pressure_ok = input(5);
  EXPECT_TRUE(read(*pressure_ok));
  clock_.advance(milliseconds(100));
  supply.drop();
  EXPECT_FALSE(supply.ok());
  EXPECT_FALSE(read(*pressure_ok));
  clock_.advance(milliseconds(50));
  supply.drop();  // already lost: nothing changes
  supply.restore();
  EXPECT_TRUE(read(*pressure_ok));
  EXPECT_THAT(chip_.history(5), ElementsAre(LevelChange{t0, true}, LevelChange{t0 + milliseconds(100), false},
                                            LevelChange{t0 + milliseconds(150), true}));
}

TEST_F(PressureSupplyTest, ActiveLowSwitchIsLowWhilePressureIsOk) {
  auto& supply = gpio_.add_simulator(
      std::make_unique<PressureSupply>(gpio_, line(5, Polarity::kActiveLow), /*ok_initially=*/true));
  EXPECT_FALSE(chip_.level(5).value());
  supply.drop();
  EXPECT_TRUE(chip_.level(5).value());
}

TEST_F(PressureSupplyTest, ListenersHearTheChangeWithItsTime) {
  struct Recorder final : PressureListener {
    std::vector<std::pair<Time, bool>> heard;
    void on_pressure_changed(Time at, bool ok) override { heard.emplace_back(at, ok); }
  } recorder;
  auto& supply = gpio_.add_simulator(std::make_unique<PressureSupply>(gpio_, line(5), true));
  supply.attach(recorder);
  clock_.advance(milliseconds(7));
  supply.drop();
  EXPECT_THAT(recorder.heard, ElementsAre(std::pair{now(), false}));
}

}  // namespace
}  // namespace hubrt::hal::fake
