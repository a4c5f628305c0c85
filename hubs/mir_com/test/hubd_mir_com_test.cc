// The real hubd on the fake backend with the hub's test board (boards/host-sim-mir-com.yaml: the MiR100
// simulator's REST server on loopback, reached through the real cpp-httplib client), commanded
// over Cyclone DDS on loopback in the test's own domain (TestDomain) like a planner: the platform
// paused before any command, a move through the mission queue, the watchdog pausing a move and
// the same command letting it go on, REST faults from /sim/fault as clear errors while the
// heartbeat goes on, a clean stop.
#include <cmath>
#include <csignal>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/runtime/lifecycle.h"
#include "hubrt/sim/sim_bridge_stage.h"

#include "hub_process.h"
#include "mir_com_messages.h"
#include "sim.h"

namespace hubrt::mir_com {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using View = hub_msgs::RobotMoverStateView;

// Generous: a busy 2-core machine running sanitizer builds in parallel; the test checks
// behaviour, not timing (a move of 2 m at the simulator's 1 m/s takes about 2 s).
constexpr auto kPatience = seconds(30);

std::string errors_of(const View& state) {
  std::string out;
  for (std::string_view error : state.error_list()) out += std::string(error) + "; ";
  return out;
}

class HubdMirComTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "test-planner");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    command_topic_.emplace(*dds::Topic<RobotMoverCommand>::create(*participant_, "/robot_mover/command"));
    command_writer_.emplace(*dds::Writer<RobotMoverCommand>::create(*participant_, *command_topic_));
    state_topic_.emplace(*dds::Topic<RobotMoverState>::create(*participant_, "/mir_com/mover/state"));
    state_reader_.emplace(*dds::Reader<RobotMoverState>::create(*participant_, *state_topic_));
    fault_topic_.emplace(
        *dds::Topic<hub_msgs_msg_dds__SimFault_>::create(*participant_, sim::kSimFaultTopic));
    fault_writer_.emplace(*dds::Writer<hub_msgs_msg_dds__SimFault_>::create(*participant_, *fault_topic_));

    integration::HubProcessOptions options;
    options.board = std::string(HUBRT_MIR_COM_DIR) + "/../../boards/host-sim-mir-com.yaml";
    options.hub = "mir_com";
    auto hub = integration::HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(state_reader_->wait_for_writers(1, kPatience)) << hub_->output();
    ASSERT_TRUE(command_writer_->wait_for_readers(1, kPatience)) << hub_->output();
    ASSERT_TRUE(fault_writer_->wait_for_readers(1, kPatience)) << hub_->output();
  }

  void TearDown() override { stop_planner(); }

  bool wait_for(const std::function<bool(const View&)>& predicate, Duration timeout = kPatience) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      const Result<bool> taken = state_reader_->take_next(state_);
      if (taken.is_ok() && taken.value()) {
        if (predicate(View(state_.get()))) return true;
        continue;
      }
      std::this_thread::sleep_for(milliseconds(2));
    }
    return false;
  }
  View last() const { return View(state_.get()); }

  // Like the planner: the wanted command, repeated every 50 ms (the timeout is 1 s).
  void command(std::string_view action, std::string_view pose = "") {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      action_ = action;
      pose_ = pose;
      planning_ = true;
    }
    if (planner_.joinable()) return;
    planner_ = std::thread([this] {
      for (;;) {
        hub_msgs::RobotMoverCommand c;
        {
          const std::lock_guard<std::mutex> lock(mutex_);
          if (!planning_) return;
          c.set_action(action_);
          c.set_pose_name(pose_);
        }
        c.set_target_type("robot_mover");
        c.set_target_name("mover");
        c.set_robot_type("MIR100");
        c.set_robot_name("mir100");
        c.set_pose_type("POSITION");
        c.set_speed_scal(1.0F);
        c.set_acc_scal(1.0F);
        if (!command_writer_->write(c.wire()).is_ok()) return;
        std::this_thread::sleep_for(milliseconds(50));
      }
    });
  }
  void stop_planner() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      planning_ = false;
    }
    if (planner_.joinable()) planner_.join();
  }

  void sim_fault(std::string fault) {
    std::string hub = "mir_com";
    std::string device = "mir";
    hub_msgs_msg_dds__SimFault_ message{hub.data(), device.data(), fault.data(), 0};
    ASSERT_TRUE(fault_writer_->write(message).is_ok());
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<RobotMoverCommand>> command_topic_;
  std::optional<dds::Writer<RobotMoverCommand>> command_writer_;
  std::optional<dds::Topic<RobotMoverState>> state_topic_;
  std::optional<dds::Reader<RobotMoverState>> state_reader_;
  std::optional<dds::Topic<hub_msgs_msg_dds__SimFault_>> fault_topic_;
  std::optional<dds::Writer<hub_msgs_msg_dds__SimFault_>> fault_writer_;
  dds::Sample<RobotMoverState> state_;
  std::optional<integration::HubProcess> hub_;
  std::mutex mutex_;  // guards action_, pose_ and planning_, shared with the planner thread
  std::string action_;
  std::string pose_;
  bool planning_ = false;
  std::thread planner_;
};

TEST_F(HubdMirComTest, MovesThePlatformAndPausesItWhenThePlannerStops) {
  // No command yet: the hub holds the platform paused.
  ASSERT_TRUE(wait_for([](const View& s) { return s.answering() && s.platform_state() == "Pause"; }))
      << hub_->output();
  EXPECT_TRUE(last().safe_hold());
  EXPECT_EQ(last().robot_name(), "mir100");

  command("move", "kit_pickup");
  ASSERT_TRUE(wait_for([](const View& s) { return s.moving() && s.fresh_msg(); })) << hub_->output();
  // Arrived (the status after the mission's Done shows where it stands).
  ASSERT_TRUE(wait_for([](const View& s) {
    return s.actual_pose() == "kit_pickup" && std::abs(s.x() - 2.0F) < 1e-3F;
  })) << errors_of(last())
      << hub_->output();
  EXPECT_EQ(last().done_action(), "moved");

  // A move to the station, and the planner goes quiet in the middle of it.
  command("move", "station");
  ASSERT_TRUE(wait_for([](const View& s) { return s.moving() && s.y() > 0.1F; })) << hub_->output();
  stop_planner();
  ASSERT_TRUE(wait_for([](const View& s) {
    return !s.fresh_msg() && s.safe_hold() && s.platform_state() == "Pause";
  })) << hub_->output();
  EXPECT_FALSE(last().moving());
  EXPECT_NE(errors_of(last()).find("command timeout"), std::string::npos) << errors_of(last());
  const float y = last().y();
  EXPECT_FALSE(wait_for([](const View&) { return false; }, seconds(1)));  // a second of States
  EXPECT_EQ(last().y(), y) << "paused: it does not move";

  // The same command again: it goes on and gets there.
  command("move", "station");
  ASSERT_TRUE(wait_for([](const View& s) {
    return s.actual_pose() == "station" && std::abs(s.y() - 1.5F) < 1e-3F;
  })) << errors_of(last());
}

TEST_F(HubdMirComTest, RestFaultsAreClearErrorsWhileTheHeartbeatGoesOn) {
  command("pause");
  ASSERT_TRUE(wait_for([](const View& s) { return s.answering() && s.done_action() == "paused"; }))
      << hub_->output();
  for (const std::string_view fault :
       {"server_error", "unauthorized", "malformed_json", "stop_answering", "go_down"}) {
    SCOPED_TRACE(fault);
    sim_fault(std::string(fault));
    const std::string expected = std::string(fault) == "server_error"     ? "HTTP 500"
                                 : std::string(fault) == "unauthorized"   ? "HTTP 401"
                                 : std::string(fault) == "malformed_json" ? "malformed JSON"
                                 : std::string(fault) == "stop_answering"
                                     ? "timeout:"
                                     : "cannot connect (refused or unreachable)";
    ASSERT_TRUE(wait_for([&](const View& s) { return errors_of(s).find(expected) != std::string::npos; }))
        << errors_of(last()) << hub_->output();
    // Not answering for answer_within_ms: not operational (recovering), held paused; States go on.
    ASSERT_TRUE(wait_for([](const View& s) {
      return !s.answering() &&
             s.header().lifecycle() == static_cast<std::uint8_t>(runtime::Lifecycle::kRecovering) &&
             s.safe_hold();
    })) << errors_of(last());
    sim_fault(std::string(fault) == "go_down" ? "come_back" : "answer");
    ASSERT_TRUE(wait_for([](const View& s) {
      return s.answering() && s.error_list().size() == 0 &&
             s.header().lifecycle() == static_cast<std::uint8_t>(runtime::Lifecycle::kOperational);
    })) << errors_of(last());
  }

  ASSERT_TRUE(hub_->process().signal(SIGTERM));
  auto status = hub_->process().wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << hub_->output();
}

}  // namespace
}  // namespace hubrt::mir_com
