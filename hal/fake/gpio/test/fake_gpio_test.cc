#include "hubrt/hal/fake/fake_gpio.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace hubrt::hal::fake {
namespace {

using std::chrono::milliseconds;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

class FakeGpioTest : public ::testing::Test {
 protected:
  FakeGpioTest() : chip_(gpio_.add_chip("sim-dock", 8)) { gpio_.add_chip("sim-rsp", 4); }

  static DigitalInputConfig input(unsigned line, Polarity polarity = Polarity::kActiveHigh) {
    DigitalInputConfig config;
    config.signal = "dock.slot.test";
    config.chip = "sim-dock";
    config.line = line;
    config.polarity = polarity;
    return config;
  }
  static DigitalOutputConfig output(unsigned line, Polarity polarity = Polarity::kActiveHigh,
                                    bool initial = false, bool safe = false) {
    DigitalOutputConfig config;
    config.signal = "rsp.test_valve";
    config.chip = "sim-dock";
    config.line = line;
    config.polarity = polarity;
    config.initial = initial;
    config.safe = safe;
    return config;
  }
  std::unique_ptr<DigitalInput> open(const DigitalInputConfig& config) {
    auto opened = gpio_.open_input(config);
    EXPECT_TRUE(opened.is_ok()) << opened.error().message;
    return opened ? std::move(*opened) : nullptr;
  }
  std::unique_ptr<DigitalOutput> open(const DigitalOutputConfig& config) {
    auto opened = gpio_.open_output(config);
    EXPECT_TRUE(opened.is_ok()) << opened.error().message;
    return opened ? std::move(*opened) : nullptr;
  }
  Time now() const { return clock_.now().mono; }
  Result<bool> read(DigitalInput& in) { return in.read(now()); }

  ManualClock clock_;
  FakeGpio gpio_{clock_};
  FakeGpioChip& chip_;
};

TEST_F(FakeGpioTest, ActiveHighInputReadsTheElectricalLevel) {
  auto in = open(input(2));
  ASSERT_TRUE(chip_.set_input_level(2, true).is_ok());
  EXPECT_TRUE(read(*in).value());
  ASSERT_TRUE(chip_.set_input_level(2, false).is_ok());
  EXPECT_FALSE(read(*in).value());
}

TEST_F(FakeGpioTest, ActiveLowInputInvertsTheElectricalLevel) {
  auto in = open(input(2, Polarity::kActiveLow));
  ASSERT_TRUE(chip_.set_input_level(2, false).is_ok());
  EXPECT_TRUE(read(*in).value());
  ASSERT_TRUE(chip_.set_input_level(2, true).is_ok());
  EXPECT_FALSE(read(*in).value());
}

TEST_F(FakeGpioTest, OutputRecordsEveryChangeWithItsTime) {
  const Time t0 = now();
  auto out = open(output(3, Polarity::kActiveLow, /*initial=*/false));
  clock_.advance(milliseconds(10));
  ASSERT_TRUE(out->write(true).is_ok());
  clock_.advance(milliseconds(5));
  ASSERT_TRUE(out->write(true).is_ok());  // same level: no change recorded
  clock_.advance(milliseconds(5));
  ASSERT_TRUE(out->write(false).is_ok());
  EXPECT_THAT(chip_.history(3), ElementsAre(LevelChange{t0, true}, LevelChange{t0 + milliseconds(10), false},
                                            LevelChange{t0 + milliseconds(20), true}));
  EXPECT_EQ(chip_.level(3).value(), true);
}

TEST_F(FakeGpioTest, OpeningAnOutputRecordsItsInitialLevelEvenWhenUnchanged) {
  auto out = open(output(3, Polarity::kActiveHigh, /*initial=*/false));
  EXPECT_THAT(chip_.history(3), ElementsAre(LevelChange{now(), false}));
}

TEST_F(FakeGpioTest, WriteSafeDrivesTheSafeLevel) {
  auto out = open(output(1, Polarity::kActiveLow, /*initial=*/true, /*safe=*/false));
  EXPECT_FALSE(chip_.level(1).value());  // active, active-low
  ASSERT_TRUE(out->write_safe().is_ok());
  EXPECT_TRUE(chip_.level(1).value());
  EXPECT_FALSE(out->safe_value());
}

TEST_F(FakeGpioTest, BiasDecidesAnUndrivenInputButNotADrivenOne) {
  DigitalInputConfig pulled_up = input(4);
  pulled_up.bias = Bias::kPullUp;
  auto up = open(pulled_up);
  EXPECT_TRUE(read(*up).value());
  DigitalInputConfig pulled_down = input(5);
  pulled_down.bias = Bias::kPullDown;
  ASSERT_TRUE(chip_.set_input_level(5, true).is_ok());
  auto down = open(pulled_down);
  EXPECT_TRUE(read(*down).value());  // a sensor drives it high
  ASSERT_TRUE(chip_.release_input(5).is_ok());
  EXPECT_FALSE(read(*down).value());  // nothing drives it: the pull-down wins
}

TEST_F(FakeGpioTest, AnOutputCannotBeDrivenFromOutside) {
  auto out = open(output(3));
  EXPECT_EQ(chip_.set_input_level(3, true).code(), ErrorCode::kFailedPrecondition);
}

TEST_F(FakeGpioTest, ListenersHearEveryChange) {
  struct Recorder final : LineListener {
    std::vector<LevelChange> heard;
    void on_line_changed(Time at, bool high) override { heard.push_back({at, high}); }
  } recorder;
  ASSERT_TRUE(chip_.watch(6, recorder).is_ok());
  auto out = open(output(6, Polarity::kActiveHigh, /*initial=*/true));
  clock_.advance(milliseconds(1));
  ASSERT_TRUE(out->write(false).is_ok());
  EXPECT_THAT(recorder.heard,
              ElementsAre(LevelChange{now() - milliseconds(1), true}, LevelChange{now(), false}));
}

TEST_F(FakeGpioTest, MissingChipIsNotFoundAndTheMessageListsTheChips) {
  DigitalInputConfig config = input(1);
  config.chip = "sim-tool";
  auto opened = gpio_.open_input(config);
  ASSERT_FALSE(opened.is_ok());
  EXPECT_EQ(opened.error().code, ErrorCode::kNotFound);
  EXPECT_EQ(opened.error().message,
            "dock.slot.test: GPIO chip with label 'sim-tool' not found; chips present: sim-dock (8 lines), "
            "sim-rsp (4 lines)");
}

TEST_F(FakeGpioTest, LineBeyondTheChipIsOutOfRange) {
  auto opened = gpio_.open_input(input(8));
  ASSERT_FALSE(opened.is_ok());
  EXPECT_EQ(opened.error().code, ErrorCode::kOutOfRange);
  EXPECT_EQ(opened.error().message,
            "dock.slot.test: line 8 is beyond GPIO chip sim-dock, which has 8 lines (0..7)");
}

TEST_F(FakeGpioTest, HeldLineIsBusyAndNamesItsHolderUntilReleased) {
  auto first = open(input(2));
  EXPECT_EQ(chip_.holder(2), "hubrt");
  auto second = gpio_.open_output(output(2));
  ASSERT_FALSE(second.is_ok());
  EXPECT_EQ(second.error().code, ErrorCode::kBusy);
  EXPECT_EQ(second.error().message, "rsp.test_valve: line 2 of sim-dock is busy, held by 'hubrt'");
  first.reset();
  EXPECT_FALSE(chip_.holder(2).has_value());
  EXPECT_TRUE(gpio_.open_output(output(2)).is_ok());
}

TEST_F(FakeGpioTest, DeniedAccessIsPermissionDenied) {
  chip_.deny_access(true);
  auto opened = gpio_.open_input(input(1));
  ASSERT_FALSE(opened.is_ok());
  EXPECT_EQ(opened.error().code, ErrorCode::kPermissionDenied);
  chip_.deny_access(false);
  EXPECT_TRUE(gpio_.open_input(input(1)).is_ok());
}

TEST_F(FakeGpioTest, InjectedReadAndWriteFaultsAreIoErrorsUntilCleared) {
  auto in = open(input(1));
  auto out = open(output(2));
  ASSERT_TRUE(chip_.fail_reads(1, true).is_ok());
  ASSERT_TRUE(chip_.fail_writes(2, true).is_ok());
  EXPECT_EQ(read(*in).status().code(), ErrorCode::kIo);
  EXPECT_EQ(out->write(true).code(), ErrorCode::kIo);
  EXPECT_FALSE(chip_.level(2).value());  // the failed write changed nothing
  ASSERT_TRUE(chip_.fail_reads(1, false).is_ok());
  ASSERT_TRUE(chip_.fail_writes(2, false).is_ok());
  EXPECT_TRUE(read(*in).is_ok());
  EXPECT_TRUE(out->write(true).is_ok());
  EXPECT_TRUE(chip_.level(2).value());
}

TEST_F(FakeGpioTest, VanishedChipMakesItsDevicesUnavailableForGood) {
  auto in = open(input(1));
  auto out = open(output(2));
  chip_.vanish();
  EXPECT_EQ(read(*in).status().code(), ErrorCode::kUnavailable);
  EXPECT_EQ(out->write(true).code(), ErrorCode::kUnavailable);
  EXPECT_EQ(out->write_safe().code(), ErrorCode::kUnavailable);
  auto reopened = gpio_.open_input(input(3));
  ASSERT_FALSE(reopened.is_ok());
  EXPECT_EQ(reopened.error().code, ErrorCode::kNotFound);
  EXPECT_THAT(reopened.error().message, HasSubstr("chips present: sim-rsp (4 lines)"));

  chip_.reappear();
  EXPECT_EQ(read(*in).status().code(), ErrorCode::kUnavailable);  // old handles stay dead
  auto fresh = gpio_.open_input(input(1));                        // its line was freed
  ASSERT_TRUE(fresh.is_ok()) << fresh.error().message;
  EXPECT_TRUE((*fresh)->read(now()).is_ok());
}

TEST_F(FakeGpioTest, CaughtPulseBetweenTwoReadsIsReportedForOneRead) {
  DigitalInputConfig config = input(2);
  config.catch_pulses = true;
  auto in = open(config);
  EXPECT_FALSE(read(*in).value());
  ASSERT_TRUE(chip_.set_input_level(2, true).is_ok());
  clock_.advance(milliseconds(1));
  ASSERT_TRUE(chip_.set_input_level(2, false).is_ok());
  EXPECT_TRUE(read(*in).value());
  EXPECT_FALSE(read(*in).value());
  EXPECT_FALSE(read(*in).value());
}

TEST_F(FakeGpioTest, CaughtLowGoingPulseOnAnActiveLowInput) {
  DigitalInputConfig config = input(2, Polarity::kActiveLow);
  config.catch_pulses = true;
  ASSERT_TRUE(chip_.set_input_level(2, true).is_ok());  // inactive
  auto in = open(config);
  EXPECT_FALSE(read(*in).value());
  ASSERT_TRUE(chip_.set_input_level(2, false).is_ok());  // active ...
  ASSERT_TRUE(chip_.set_input_level(2, true).is_ok());   // ... and gone again
  EXPECT_TRUE(read(*in).value());
  EXPECT_FALSE(read(*in).value());
}

TEST_F(FakeGpioTest, WithoutCatchPulsesAPulseBetweenReadsIsLost) {
  auto in = open(input(2));
  EXPECT_FALSE(read(*in).value());
  ASSERT_TRUE(chip_.set_input_level(2, true).is_ok());
  ASSERT_TRUE(chip_.set_input_level(2, false).is_ok());
  EXPECT_FALSE(read(*in).value());
}

TEST(FakeGpioHistory, KeepsOnlyTheLastChangesAndStillCatchesPulsesBeyondThem) {
  ManualClock clock;
  FakeGpio gpio(clock);
  FakeGpioChip& chip = gpio.add_chip("c", 1, /*history_capacity=*/4);
  DigitalInputConfig config;
  config.signal = "s";
  config.chip = "c";
  config.catch_pulses = true;
  auto in = std::move(*gpio.open_input(config));
  EXPECT_FALSE(in->read(clock.now().mono).value());
  for (int i = 0; i < 10; ++i) {
    clock.advance(milliseconds(1));
    ASSERT_TRUE(chip.set_input_level(0, i % 2 == 0).is_ok());
  }
  const auto history = chip.history(0);
  ASSERT_EQ(history.size(), 4U);
  EXPECT_EQ(history.back().at, clock.now().mono);
  EXPECT_FALSE(history.back().high);
  EXPECT_TRUE(in->read(clock.now().mono).value());  // the line went high in between
}

}  // namespace
}  // namespace hubrt::hal::fake
