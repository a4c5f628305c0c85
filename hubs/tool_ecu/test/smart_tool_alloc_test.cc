// The smart tool node's steady-state cycle allocates nothing: the generic Node (intake,
// validation, echo, State) around SmartToolLogic, on the fake backend, through tightenings,
// a loosen, a change of command mid-run, an interlock dropping and the controller getting lost.
#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/fake_backend.h"
#include "hubrt/hub_api/node_wiring.h"

#include "alloc_counter.h"
#include "smart_tool_logic.h"
#include "tool_ecu_hub_type.h"

namespace hubrt::tool_ecu {
namespace {

using hubrt::testing::AllocationScope;
using std::chrono::milliseconds;
using Wire = hub_msgs::SmartToolCommand::Wire;

// Hands the node the planner's command of the moment, every cycle (as the planner repeats it).
class RepeatingSource final : public runtime::CommandSource<Wire> {
 public:
  void set(const hub_msgs::SmartToolCommand& command) { command_ = command; }
  Result<runtime::ReceivedCommand<Wire>> next() noexcept override {
    if (given_) {
      given_ = false;
      return runtime::ReceivedCommand<Wire>{};
    }
    given_ = true;
    return runtime::ReceivedCommand<Wire>{&command_.wire(), std::nullopt, std::nullopt};
  }

 private:
  hub_msgs::SmartToolCommand command_;
  bool given_ = false;
};

class CountingSink final : public runtime::StateSink<hub_msgs::SmartToolState::Wire> {
 public:
  Status publish(const hub_msgs::SmartToolState::Wire& /*state*/) noexcept override {
    ++published;
    return Status::ok();
  }
  std::uint64_t published = 0;
};

TEST(SmartToolSteadyCycle, AllocatesNothing) {
  ManualClock clock;
  auto board = hal::load_board(std::string(HUBRT_BOARDS_DIR) + "/host-sim.yaml");
  ASSERT_TRUE(board) << board.error().message;
  auto config = config::load_hub_config(std::string(HUBRT_HUBS_DIR) + "/tool_ecu/tool_ecu.yaml");
  ASSERT_TRUE(config) << config.error().message;
  auto settings = parse_smart_tool_settings(config->nodes.at(0));
  ASSERT_TRUE(settings) << settings.error().message;
  auto fake = hal::fake::FakeBackend::create(*board, clock);
  ASSERT_TRUE(fake) << fake.error().message;
  hub_api::RemoteState<hub_msgs::RspStateView> rsp{"rsp", "/rsp_ecu/rsp/state", milliseconds(500),
                                                   hub_msgs_msg_dds__RspState__desc, 0};
  hub_msgs::RspStateRef(*static_cast<hub_msgs::RspState::Wire*>(rsp.sample_data())).set_tool("smart_tool");
  auto devices = open_smart_tool_devices(*settings, *board, **fake, clock.now().mono);
  ASSERT_TRUE(devices) << devices.error().message;
  auto logic = SmartToolLogic::create(*settings, std::move(*devices), std::make_unique<RspToolHolder>(rsp),
                                      clock.now().mono);
  ASSERT_TRUE(logic) << logic.error().message;
  RepeatingSource source;
  CountingSink sink;
  runtime::NodeOptions options;
  options.name = "tool";
  runtime::Node<SmartToolLogic> node(options, std::move(*logic), source, sink, hub_api::message_ops<Wire>());
  hal::fake::SmartToolSimulator* tool = (*fake)->smart_tool("tool_bus");
  (*fake)->input("tool.arm.home")->set(false);

  hub_msgs::SmartToolCommand command;
  command.set_target_type("smart_tool");
  command.set_target_name("tool");
  command.set_action("tighten");
  command.set_run_id(1);
  command.set_program("ladder_frame_bolt");
  const auto run = [&](int cycles) {
    for (int i = 0; i < cycles; ++i) {
      clock.advance(milliseconds(50));
      rsp.note_arrival(clock.now().mono);
      source.set(command);
      node.step(clock.now());
      ASSERT_TRUE(node.publish(clock.now()).is_ok());
    }
  };
  // Warm-up: a whole tightening (first log messages size spdlog's caches, as hubd's start-up
  // logging does long before its first cycle), a controller lost and back, a reset.
  run(40);
  tool->power_off();
  run(10);
  tool->power_on();
  command.set_action("reset");
  run(5);

  AllocationScope scope;
  for (std::uint32_t bolt = 2; bolt < 6; ++bolt) {
    command.set_action("tighten");
    command.set_run_id(bolt);
    run(bolt % 2 == 0 ? 30 : 5);  // odd bolts are interrupted by the next one
  }
  const int runs_after_reboot = tool->snapshot().run_counter;  // counts from 0 after the reboot
  command.set_action("loosen");
  run(10);
  command.set_action("idle");
  run(5);
  tool->power_off();
  run(10);
  tool->power_on();
  run(5);
  command.set_action("reset");
  run(5);
  const std::size_t allocations = scope.count();

  EXPECT_EQ(allocations, 0u);
  // It really ran: runs happened and the State says the last one.
  EXPECT_GE(runs_after_reboot, 4);
  EXPECT_EQ(node.state().last_result().run_id(), 5u);
  EXPECT_GT(sink.published, 100u);
}

}  // namespace
}  // namespace hubrt::tool_ecu
