#include "hubrt/hal/common/debouncer.h"

#include <gtest/gtest.h>

namespace hubrt::hal {
namespace {

using std::chrono::milliseconds;

class DebouncerTest : public ::testing::Test {
 protected:
  ManualClock clock_;
  Time now() const { return clock_.now().mono; }
};

TEST_F(DebouncerTest, FirstSampleIsReportedAsItIs) {
  Debouncer debouncer(milliseconds(20));
  EXPECT_FALSE(debouncer.level().has_value());
  EXPECT_TRUE(debouncer.update(true, now()));
  EXPECT_EQ(debouncer.level(), true);
}

TEST_F(DebouncerTest, HeldChangeIsReportedExactlyAtTheWindow) {
  Debouncer debouncer(milliseconds(20));
  EXPECT_FALSE(debouncer.update(false, now()));
  EXPECT_FALSE(debouncer.update(true, now()));  // change starts
  clock_.advance(milliseconds(19));
  EXPECT_FALSE(debouncer.update(true, now()));
  clock_.advance(milliseconds(1));
  EXPECT_TRUE(debouncer.update(true, now()));  // held for exactly 20 ms
}

TEST_F(DebouncerTest, OneNanosecondShortOfTheWindowIsNotEnough) {
  Debouncer debouncer(milliseconds(20));
  debouncer.update(false, now());
  debouncer.update(true, now());
  clock_.advance(milliseconds(20) - std::chrono::nanoseconds(1));
  EXPECT_FALSE(debouncer.update(true, now()));
}

TEST_F(DebouncerTest, BounceShorterThanTheWindowIsIgnored) {
  Debouncer debouncer(milliseconds(20));
  debouncer.update(false, now());
  for (int i = 0; i < 5; ++i) {  // 5 ms bounces: up, down, up, down ...
    EXPECT_FALSE(debouncer.update(true, now()));
    clock_.advance(milliseconds(5));
    EXPECT_FALSE(debouncer.update(false, now()));
    clock_.advance(milliseconds(5));
  }
  clock_.advance(milliseconds(100));
  EXPECT_FALSE(debouncer.update(false, now()));
}

TEST_F(DebouncerTest, BounceRestartsTheWindow) {
  Debouncer debouncer(milliseconds(20));
  debouncer.update(false, now());
  debouncer.update(true, now());
  clock_.advance(milliseconds(15));
  debouncer.update(false, now());  // bounced back: the candidate is dropped
  clock_.advance(milliseconds(1));
  debouncer.update(true, now());  // new candidate from here
  clock_.advance(milliseconds(19));
  EXPECT_FALSE(debouncer.update(true, now()));
  clock_.advance(milliseconds(1));
  EXPECT_TRUE(debouncer.update(true, now()));
}

TEST_F(DebouncerTest, ReleaseIsDebouncedToo) {
  Debouncer debouncer(milliseconds(10));
  debouncer.update(true, now());
  debouncer.update(false, now());
  clock_.advance(milliseconds(9));
  EXPECT_TRUE(debouncer.update(false, now()));
  clock_.advance(milliseconds(1));
  EXPECT_FALSE(debouncer.update(false, now()));
}

TEST_F(DebouncerTest, ZeroWindowPassesEverySampleThrough) {
  Debouncer debouncer(Duration::zero());
  EXPECT_FALSE(debouncer.update(false, now()));
  EXPECT_TRUE(debouncer.update(true, now()));
  EXPECT_FALSE(debouncer.update(false, now()));
  EXPECT_TRUE(debouncer.update(true, now()));
}

TEST_F(DebouncerTest, ResetReportsTheNextSampleAsItIs) {
  Debouncer debouncer(milliseconds(50));
  debouncer.update(false, now());
  debouncer.reset();
  EXPECT_FALSE(debouncer.level().has_value());
  EXPECT_TRUE(debouncer.update(true, now()));
}

}  // namespace
}  // namespace hubrt::hal
