// The smart tool node's test fixture: the logic on the fake backend (the simulated controller on
// a virtual CAN bus, fake GPIO) with a manual clock, cycled as the Node runs it. Shared by the
// logic's test files.
#pragma once

#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/fake_backend.h"

#include "smart_tool_logic.h"
#include "tool_ecu_hub_type.h"

namespace hubrt::tool_ecu::testing {

// The node as the hub type builds it: its devices opened from the board, then handed in.
inline Expected<SmartToolLogic> make_smart_tool_logic(const SmartToolSettings& settings,
                                                      const hal::BoardConfig& board, hal::Backend& backend,
                                                      std::unique_ptr<ToolHolderView> holder, Time now) {
  auto devices = open_smart_tool_devices(settings, board, backend, now);
  if (!devices) return std::move(devices).error();
  return SmartToolLogic::create(settings, std::move(*devices), std::move(holder), now);
}

namespace st = protocol::smart_tool;
using hal::fake::FakeBackend;
using std::chrono::milliseconds;

constexpr auto kCycle = milliseconds(50);

// A command as the planner sends it; the strings live here.
struct Order {
  std::string action;
  std::uint32_t run_id = 0;
  std::string program;
  std::string target_name = "tool";
  std::string target_type = "smart_tool";

  [[nodiscard]] hub_msgs::SmartToolCommand message() const {
    hub_msgs::SmartToolCommand command;
    command.set_target_type(target_type);
    command.set_target_name(target_name);
    command.set_action(action);
    command.set_run_id(run_id);
    command.set_program(program);
    return command;
  }
};

inline Order tighten(std::uint32_t run_id, std::string program = "ladder_frame_bolt") {
  Order order;
  order.action = "tighten";
  order.run_id = run_id;
  order.program = std::move(program);
  return order;
}
inline Order action(std::string name) {
  Order order;
  order.action = std::move(name);
  return order;
}

class SmartToolLogicTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto board = hal::load_board(std::string(HUBRT_BOARDS_DIR) + "/host-sim.yaml");
    ASSERT_TRUE(board) << board.error().message;
    board_ = std::move(*board);
    auto config = config::load_hub_config(std::string(HUBRT_HUBS_DIR) + "/tool_ecu/tool_ecu.yaml");
    ASSERT_TRUE(config) << config.error().message;
    for (const auto& node : config->nodes) {
      if (node.type == SmartToolLogic::kType) {
        auto settings = parse_smart_tool_settings(node);
        ASSERT_TRUE(settings) << settings.error().message;
        settings_ = std::move(*settings);
      }
    }
    auto fake = FakeBackend::create(board_, clock_);
    ASSERT_TRUE(fake) << fake.error().message;
    fake_ = std::move(*fake);
    tool_ = fake_->smart_tool("tool_bus");
    ASSERT_NE(tool_, nullptr);
    set_tool_on_robot("smart_tool");
    auto logic = make_smart_tool_logic(settings_, board_, *fake_, std::make_unique<RspToolHolder>(rsp_),
                                       clock_.now().mono);
    ASSERT_TRUE(logic) << logic.error().message;
    logic_.emplace(std::move(*logic));
  }

  // The RSP ECU's State says which tool is on the robot; it stays fresh while rsp_alive_.
  void set_tool_on_robot(std::string_view tool) {
    hub_msgs::RspStateRef(*static_cast<hub_msgs::RspState::Wire*>(rsp_.sample_data())).set_tool(tool);
    rsp_.note_arrival(clock_.now().mono);
  }

  // One cycle as the Node runs it, `kCycle` after the previous one.
  void cycle(const Order* order) {
    clock_.advance(kCycle);
    const Time now = clock_.now().mono;
    if (rsp_alive_) rsp_.note_arrival(now);
    if (order != nullptr) command_ = order->message();
    logic_->read_inputs(now);
    const hub_msgs::SmartToolCommandView in_force = command_.view();
    logic_->update(order == nullptr ? nullptr : &in_force, now);
    errors_.clear();
    state_ = hub_msgs::SmartToolState();
    logic_->report(state_, errors_, now);
  }
  void cycles(const Order* order, int n) {
    for (int i = 0; i < n; ++i) cycle(order);
  }
  void cycles(const Order& order, int n) { cycles(&order, n); }
  // Cycles until `done` holds; false after `limit` cycles.
  template <class Predicate>
  bool cycle_until(const Order* order, Predicate done, int limit = 100) {
    for (int i = 0; i < limit; ++i) {
      cycle(order);
      if (done()) return true;
    }
    return false;
  }
  // A reset command taking effect: the Node calls reset() first, then runs the cycle on it.
  void reset_command() {
    logic_->reset();
    const Order reset = action("reset");
    cycle(&reset);
  }

  // The arm leaves home: no sensor active is the operating position.
  void arm_to_operating() {
    fake_->input("tool.arm.home")->set(false);
    cycles(nullptr, 2);  // past the 10 ms debounce
    ASSERT_EQ(logic_->arm_position(), ArmPosition::kOperating);
  }
  // Controller heard, status in, arm operating, robot holding the tool: a tighten can start.
  void make_ready() {
    arm_to_operating();
    ASSERT_TRUE(cycle_until(nullptr, [&] { return state_.controller_online(); }));
    cycles(nullptr, 3);  // a periodic status (every 100 ms) has arrived
  }

  [[nodiscard]] std::string output() const { return std::string(state_.output()); }
  [[nodiscard]] std::string blocked_by() const { return std::string(state_.blocked_by()); }
  [[nodiscard]] std::string errors() const {
    std::string out;
    for (std::size_t i = 0; i < errors_.size(); ++i) out += std::string(errors_.at(i)) + "; ";
    return out;
  }
  [[nodiscard]] bool line(std::string_view signal) { return fake_->active(signal).value(); }
  // Runs tighten `run_id` to its end; true when it ended with a result for it.
  bool tighten_to_the_end(const Order& order) {
    return cycle_until(&order, [&] {
      return state_.last_result().run_id() == order.run_id && state_.output() == std::string("idle") &&
             std::string(state_.activity()) == "idle";
    });
  }

  // Records the run lines' changes in the order they happen (declared before the chip's owner).
  struct LineChanges {
    struct Listener final : hal::fake::LineListener {
      Listener(std::vector<std::string>& out, char name) : sequence(&out), letter(name) {}
      void on_line_changed(Time /*at*/, bool high) override {
        sequence->push_back(std::string{letter, high ? '1' : '0'});
      }
      std::vector<std::string>* sequence;
      char letter;
    };
    std::vector<std::string> sequence;
    Listener forward{sequence, 'F'};
    Listener reverse{sequence, 'R'};
  };

  ManualClock clock_;
  hal::BoardConfig board_;
  SmartToolSettings settings_;
  LineChanges line_changes_;
  std::unique_ptr<FakeBackend> fake_;
  hal::fake::SmartToolSimulator* tool_ = nullptr;
  hub_api::RemoteState<hub_msgs::RspStateView> rsp_{"rsp", "/rsp_ecu/rsp/state", milliseconds(500),
                                                    hub_msgs_msg_dds__RspState__desc, 0};
  bool rsp_alive_ = true;
  std::optional<SmartToolLogic> logic_;
  hub_msgs::SmartToolCommand command_;
  hub_msgs::SmartToolState state_;
  runtime::ErrorList errors_;
};
}  // namespace hubrt::tool_ecu::testing
