#include "hubrt/hal/fake/settable_input.h"

#include <gmock/gmock.h>

#include "sim_test_support.h"

namespace hubrt::hal::fake {
namespace {

using std::chrono::milliseconds;
using ::testing::ElementsAre;

class SettableInputTest : public SimTest {};

TEST_F(SettableInputTest, DrivesTheLineThroughItsPolarity) {
  auto& button = gpio_.add_simulator(
      std::make_unique<SettableInput>(gpio_, line(3, Polarity::kActiveLow), /*initially_active=*/false));
  auto in = input(3, Polarity::kActiveLow);
  EXPECT_TRUE(chip_.level(3).value());  // inactive on an active-low line is high
  EXPECT_FALSE(read(*in));
  button.set(true);
  EXPECT_FALSE(chip_.level(3).value());
  EXPECT_TRUE(read(*in));
}

TEST_F(SettableInputTest, PulseEndsExactlyAfterItsWidth) {
  auto& blip = gpio_.add_simulator(std::make_unique<SettableInput>(gpio_, line(4), false));
  const Time t0 = now();
  blip.pulse(milliseconds(3));
  clock_.advance(milliseconds(10));
  EXPECT_THAT(chip_.history(4), ElementsAre(LevelChange{t0, true}, LevelChange{t0 + milliseconds(3), false}));
  EXPECT_FALSE(blip.active());
}

TEST_F(SettableInputTest, SetCancelsAPulseInProgress) {
  auto& blip = gpio_.add_simulator(std::make_unique<SettableInput>(gpio_, line(4), false));
  blip.pulse(milliseconds(3));
  clock_.advance(milliseconds(1));
  blip.set(true);
  clock_.advance(milliseconds(10));
  EXPECT_TRUE(chip_.level(4).value());
}

}  // namespace
}  // namespace hubrt::hal::fake
