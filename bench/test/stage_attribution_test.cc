// bench/support/stage_attribution: a slow round trip put down to the hub or to the host.
#include "stage_attribution.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

namespace hubrt::bench {
namespace {

class StageTraceFile : public ::testing::Test {
 protected:
  void TearDown() override { std::filesystem::remove(path_); }
  std::string write(const std::string& text) {
    std::ofstream(path_) << text;
    return path_;
  }
  std::string path_ =
      (std::filesystem::temp_directory_path() / fmt::format("hubrt-stage-attribution-{}.csv", getpid()))
          .string();
};

TEST_F(StageTraceFile, ReadsCompleteStepsSortedAndSkipsThoseWithoutAnEffect) {
  auto steps =
      read_stage_trace(write("# hubd stage trace: 3 command steps, 0 dropped\n"
                             "listener_ns,woke_ns,stepped_ns,written_ns\n"
                             "500,510,520,530\n"
                             "100,110,0,0\n"
                             "200,210,220,230\n"));
  ASSERT_TRUE(steps) << steps.error().message;
  ASSERT_EQ(steps->size(), 2u) << "the step without an effect is left out";
  EXPECT_EQ((*steps)[0].listener, 200);
  EXPECT_EQ((*steps)[1].written, 530);
}

TEST_F(StageTraceFile, ABrokenLineIsAnErrorNamingFileAndLine) {
  auto steps = read_stage_trace(write("listener_ns,woke_ns,stepped_ns,written_ns\n1,2,3\n"));
  ASSERT_FALSE(steps);
  EXPECT_NE(steps.error().message.find(":2: not four numbers"), std::string::npos) << steps.error().message;
  EXPECT_FALSE(read_stage_trace(write("1,2,3,4 5\n")));
  EXPECT_FALSE(read_stage_trace(path_ + ".missing"));
}

TEST(StageAttribution, EachPartOfTheRoundTripIsTakenFromTheStampsAroundIt) {
  const std::vector<TracedStep> steps = {{1'000, 1'100, 1'200, 1'300}, {10'000, 10'100, 18'000, 18'100}};
  const Attribution a = attribute({9'500, 19'500}, steps);
  ASSERT_TRUE(a.traced);
  EXPECT_EQ(a.to_listener, 500);
  EXPECT_EQ(a.wake, 100);
  EXPECT_EQ(a.step, 7'900);
  EXPECT_EQ(a.write, 100);
  EXPECT_EQ(a.from_written, 1'400);
  const Attribution b = attribute({0, 5'000}, steps);
  ASSERT_TRUE(b.traced);
  EXPECT_EQ(b.to_listener, 1'000) << "the first step, not the second";
  EXPECT_EQ(b.from_written, 3'700);
}

Attribution parts(std::int64_t to_listener, std::int64_t wake, std::int64_t step, std::int64_t write,
                  std::int64_t from_written) {
  return {true, to_listener, wake, step, write, from_written};
}

TEST(StageAttribution, ASlowRoundTripIsPutDownToThePartThatGrewTheMost) {
  // Typical: 40 us to the listener, 10 wake, 30 step, 20 write, 40 back; an untraced one and an
  // outlier do not move the medians.
  const std::vector<Attribution> all = {parts(40, 10, 30, 20, 40), parts(41, 11, 29, 20, 39),
                                        parts(39, 9, 31, 21, 41), Attribution{}, parts(900, 10, 30, 20, 40)};
  const Attribution typical = typical_of(all);
  ASSERT_TRUE(typical.traced);
  EXPECT_EQ(typical.to_listener, 41);
  EXPECT_EQ(typical.step, 30);
  // The step took 200 us more: the hub's, though the outside parts are larger in absolute terms.
  EXPECT_EQ(late_stage(parts(50, 10, 230, 20, 50), typical), LateStage::kStep);
  EXPECT_TRUE(in_hub(LateStage::kStep));
  // The cycle thread woke late.
  EXPECT_EQ(late_stage(parts(40, 300, 30, 20, 40), typical), LateStage::kWake);
  // The command was late to the listener: the host's or the transport's.
  EXPECT_EQ(late_stage(parts(900, 10, 30, 20, 40), typical), LateStage::kToListener);
  EXPECT_FALSE(in_hub(LateStage::kToListener));
  EXPECT_EQ(late_stage(parts(40, 10, 30, 20, 500), typical), LateStage::kFromWritten);
  EXPECT_FALSE(in_hub(LateStage::kFromWritten));
  EXPECT_FALSE(typical_of({Attribution{}}).traced);
}

TEST(StageAttribution, AStepOutsideTheRoundTripIsNotItsOwn) {
  const std::vector<TracedStep> steps = {{1'000, 1'100, 1'200, 1'300}};
  EXPECT_FALSE(attribute({2'000, 3'000}, steps).traced) << "listener before the command was sent";
  EXPECT_FALSE(attribute({0, 1'250}, steps).traced) << "written after the echo was taken";
  EXPECT_FALSE(attribute({0, 900}, steps).traced);
  EXPECT_FALSE(attribute({0, 5'000}, {}).traced);
}

}  // namespace
}  // namespace hubrt::bench
