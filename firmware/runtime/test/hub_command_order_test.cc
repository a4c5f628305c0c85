// A command step steps the nodes a command may be waiting for first (issue 16 point 8: the echo
// of a command for one node must not wait behind the other nodes' work), then the others, each
// exactly once; a periodic cycle keeps the order the nodes were added in.
#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/runtime/hub.h"
#include "hubrt/runtime/node.h"
#include "hubrt/runtime/reflected_message_ops.h"

#include "node_test_support.h"
#include "valve_test_reflect.h"

namespace hubrt::runtime::testing {
namespace {

using std::chrono::milliseconds;

// What happened, in order, across the nodes: "<node> next" when a node looked for commands (the
// start of its step), "<node> published" when it published its State.
using Log = std::vector<std::string>;

// A queue of commands that logs each look and says whether one is waiting, as the DDS source does.
class LoggingSource final : public CommandSource<ValveCommand> {
 public:
  LoggingSource(std::string node, Log& log) : node_(std::move(node)), log_(log) {}
  Result<ReceivedCommand<ValveCommand>> next() noexcept override {
    log_.push_back(node_ + " next");
    return queue_.next();
  }
  [[nodiscard]] bool may_have_command() const noexcept override { return queue_.pending() > 0; }
  QueueSource& queue() { return queue_; }

 private:
  std::string node_;
  Log& log_;
  QueueSource queue_;
};

class LoggingSink final : public StateSink<ValveState> {
 public:
  LoggingSink(std::string node, Log& log) : node_(std::move(node)), log_(log) {}
  Status publish(const ValveState& /*state*/) noexcept override {
    log_.push_back(node_ + " published");
    return Status::ok();
  }

 private:
  std::string node_;
  Log& log_;
};

class HubCommandOrderTest : public ::testing::Test {
 protected:
  HubCommandOrderTest() {
    HubOptions options;
    options.name = "hub";
    options.period = milliseconds(10);
    hub_ = std::make_unique<Hub>(std::move(options));
    for (std::size_t i = 0; i < kNodes; ++i) {
      NodeOptions node;
      node.name = names_[i];
      hub_->add_node(
          std::make_unique<Node<ValveLogic>>(node, ValveLogic(worlds_[i]), sources_[i], sinks_[i], ops_));
    }
  }
  void command(std::size_t node, const char* action) {
    OwnedValveCommand c;
    c.target_name = names_[node];
    c.action = action;
    sources_[node].queue().push(c);
  }
  // Index of the first entry `what` in the log (log size when absent).
  std::size_t at(const std::string& what) const {
    std::size_t i = 0;
    while (i < log_.size() && log_[i] != what) ++i;
    return i;
  }
  std::size_t count(const std::string& what) const {
    return static_cast<std::size_t>(std::count(log_.begin(), log_.end(), what));
  }

  static constexpr std::size_t kNodes = 3;
  std::array<std::string, kNodes> names_{"a", "b", "c"};
  Log log_;
  std::array<ValveWorld, kNodes> worlds_{};
  std::array<LoggingSource, kNodes> sources_{LoggingSource("a", log_), LoggingSource("b", log_),
                                             LoggingSource("c", log_)};
  std::array<LoggingSink, kNodes> sinks_{LoggingSink("a", log_), LoggingSink("b", log_),
                                         LoggingSink("c", log_)};
  ReflectedMessageOps ops_{msgs::type_info_of<ValveCommand>()};
  ManualClock clock_;
  std::unique_ptr<Hub> hub_;
};

TEST_F(HubCommandOrderTest, TheCommandedNodeEchoesBeforeTheOtherNodesStep) {
  hub_->cycle(clock_.now());
  clock_.advance(milliseconds(3));
  log_.clear();
  command(2, "open");  // for the last node added
  hub_->command_step(clock_.now());
  ASSERT_EQ(count("c published"), 1u) << "the command took effect and was echoed at once";
  EXPECT_LT(at("c published"), at("a next")) << "node a stepped before c's echo went out";
  EXPECT_LT(at("c published"), at("b next")) << "node b stepped before c's echo went out";
  EXPECT_EQ(count("a next"), 1u) << "every node still steps, once";
  EXPECT_EQ(count("b next"), 1u);
  EXPECT_EQ(count("a published") + count("b published"), 0u) << "nothing changed for a and b";
  EXPECT_TRUE(worlds_[2].open);
}

TEST_F(HubCommandOrderTest, SeveralCommandedNodesKeepTheirOrderAndGoFirst) {
  hub_->cycle(clock_.now());
  clock_.advance(milliseconds(3));
  log_.clear();
  command(2, "open");
  command(1, "open");
  hub_->command_step(clock_.now());
  EXPECT_LT(at("b published"), at("c next"));
  EXPECT_LT(at("c published"), at("a next"));
  EXPECT_EQ(count("a next"), 1u);
}

TEST_F(HubCommandOrderTest, APeriodicCycleStepsTheNodesInTheirOrder) {
  command(2, "open");
  hub_->cycle(clock_.now());
  EXPECT_LT(at("a published"), at("b next"));
  EXPECT_LT(at("b published"), at("c next"));
  EXPECT_EQ(count("c published"), 1u) << "the heartbeat carries c's command";
}

}  // namespace
}  // namespace hubrt::runtime::testing
