#include "hubrt/hal/common/debounced_input.h"

#include <gtest/gtest.h>

namespace hubrt::hal {
namespace {

using std::chrono::milliseconds;

// An input whose raw level and failure the test sets directly.
class ScriptedInput final : public DigitalInput {
 public:
  bool level = false;
  Status failure = Status::ok();
  int reads = 0;

 private:
  Result<bool> do_read(Time /*now*/) noexcept override {
    ++reads;
    if (!failure.is_ok()) return failure;
    return level;
  }
};

class DebouncedInputTest : public ::testing::Test {
 protected:
  DebouncedInputTest() {
    auto inner = std::make_unique<ScriptedInput>();
    raw_ = inner.get();
    input_ = std::make_unique<DebouncedInput>(std::move(inner), milliseconds(20));
  }
  Result<bool> read() { return input_->read(clock_.now().mono); }

  ManualClock clock_;
  ScriptedInput* raw_ = nullptr;
  std::unique_ptr<DebouncedInput> input_;
};

TEST_F(DebouncedInputTest, ReportsAChangeOnlyAfterItHeldForTheWindow) {
  EXPECT_FALSE(read().value());
  raw_->level = true;
  EXPECT_FALSE(read().value());
  clock_.advance(milliseconds(10));
  EXPECT_FALSE(read().value());
  clock_.advance(milliseconds(10));
  EXPECT_TRUE(read().value());
}

TEST_F(DebouncedInputTest, IgnoresBouncesShorterThanTheWindow) {
  EXPECT_FALSE(read().value());
  for (int i = 0; i < 4; ++i) {
    raw_->level = !raw_->level;
    clock_.advance(milliseconds(8));
    EXPECT_FALSE(read().value());
  }
}

TEST_F(DebouncedInputTest, PassesErrorsThroughAndKeepsItsState) {
  EXPECT_FALSE(read().value());
  raw_->level = true;
  EXPECT_FALSE(read().value());  // candidate starts here
  raw_->failure = Status(ErrorCode::kIo);
  clock_.advance(milliseconds(20));
  const Result<bool> failed = read();
  ASSERT_FALSE(failed.is_ok());
  EXPECT_EQ(failed.status().code(), ErrorCode::kIo);
  raw_->failure = Status::ok();
  EXPECT_TRUE(read().value());  // the candidate survived the failed read
}

TEST(Debounce, ZeroWindowReturnsTheInputUnwrapped) {
  auto inner = std::make_unique<ScriptedInput>();
  DigitalInput* raw = inner.get();
  EXPECT_EQ(debounce(std::move(inner), Duration::zero()).get(), raw);
}

TEST(Debounce, PositiveWindowWrapsTheInput) {
  ManualClock clock;
  auto inner = std::make_unique<ScriptedInput>();
  ScriptedInput* raw = inner.get();
  auto input = debounce(std::move(inner), milliseconds(5));
  ASSERT_NE(input.get(), raw);
  EXPECT_FALSE(input->read(clock.now().mono).value());
  raw->level = true;
  EXPECT_FALSE(input->read(clock.now().mono).value());
  EXPECT_EQ(raw->reads, 2);
}

}  // namespace
}  // namespace hubrt::hal
