// The tool changer's steady cycle allocates nothing: commands repeated and changing, an unlock
// refused every cycle (reasons formatted into error_list and the rejection), the Dock ECU State
// going stale (the loss reason formatted), a latched pressure fault reported.
#include <gtest/gtest.h>
#include <spdlog/sinks/null_sink.h>
#include <spdlog/spdlog.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/fake_backend.h"
#include "hubrt/hub_api/node_wiring.h"
#include "hubrt/runtime/node.h"

#include "alloc_counter.h"
#include "rsp_logic.h"
#include "rsp_test_support.h"

namespace hubrt::rsp_ecu {
namespace {

using hubrt::testing::AllocationScope;
using std::chrono::milliseconds;
using testing::command;
using testing::dock_slots;
using testing::DockFeed;
using testing::NullSink;
using testing::OwnedCommand;
using testing::QueueSource;

// The shipped board and hub file on the fake backend: RspLogicTest's set-up.
class RspCycle : public testing::RspLogicTest {};

TEST_F(RspCycle, TheCounterSeesAnAllocation) {
  AllocationScope scope;
  auto* text = new std::string(100, 'x');  // NOLINT: deliberately allocating to prove the counter works
  delete text;                             // NOLINT
  EXPECT_GE(scope.count(), 1u);
}

TEST_F(RspCycle, AllocatesNothingInSteadyState) {
  ManualClock& clock = clock_;
  DockFeed& dock = dock_;
  RspLogic logic = make_logic();
  ASSERT_FALSE(HasFailure());
  QueueSource source;
  NullSink sink;
  runtime::NodeOptions options;
  options.name = "rsp";
  options.log = std::make_shared<spdlog::logger>("rsp", std::make_shared<spdlog::sinks::null_sink_mt>());
  runtime::Node<RspLogic> node(options, std::move(logic), source, sink,
                               hub_api::message_ops<hub_msgs::RspCommand::Wire>());

  // Every command queued up front (the queue allocates); the smart tool is not home, so every
  // unlock is refused. The Dock ECU goes quiet after cycle 300.
  constexpr int kCycles = 600;
  const OwnedCommand commands[] = {command("lock", "grab"), command("lock", "keep"),
                                   command("unlock", "grab")};
  for (int i = 0; i < kCycles; ++i) source.push(commands[(i / 10) % 3]);
  dock.arrive(dock_slots(true, true, false), clock.now().mono);

  const auto run = [&](int from, int to) {
    for (int i = from; i < to; ++i) {
      if (i < 300 && i % 10 == 0) {
        // A Dock State arriving is the subscription stage's work (Cyclone fills the sample); here
        // only its arrival is noted so that the test's own allocation stays out of the count.
        dock.input().note_arrival(clock.now().mono);
      }
      if (i == 450) fake_->pressure_supply("main_air")->drop();
      node.step(clock.now());
      clock.advance(milliseconds(10));
    }
  };
  run(0, 40);  // warm-up: first log messages and formats
  AllocationScope scope;
  run(40, kCycles);
  EXPECT_EQ(scope.count(), 0u);
  // Guard against a vacuous pass: the paths above really ran.
  EXPECT_GT(node.rejected(), 0u);
  EXPECT_TRUE(node.errors().contains("pressure failure"));
  EXPECT_FALSE(node.logic().unlock_allowed());
}

}  // namespace
}  // namespace hubrt::rsp_ecu
