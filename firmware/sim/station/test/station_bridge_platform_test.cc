// hubsim's bridge over DDS with a fake mobile platform: a RobotMoverState (node-type layout) or
// MirComState (hub layout) written on the configured topic makes the StationState report the kit
// at the station with the ladder frame on it, then away with the frame. The model's time is a
// manual clock; only DDS delivery takes wall time.
#include <cstring>
#include <optional>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include "hubrt/dds/participant.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/sim/station/station_bridge.h"
#include "hubrt/test_support/test_domain.h"

#include "mir_com_typed.h"  // registers RobotMoverState_ and MirComState_ as topic types

namespace hubrt::sim::station {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using RobotMoverState = hub_msgs_msg_dds__RobotMoverState_;
using MirComState = hub_msgs_msg_dds__MirComState_;
using StationState = hub_msgs_msg_dds__StationState_;

// Discovery and delivery on a loaded machine (2 cores shared by parallel builds): generous.
constexpr Duration kDeliveryBound = seconds(20);
constexpr Duration kStep = milliseconds(20);

StationConfig config_with_platform(std::string topic, std::string field) {
  StationConfig config;
  for (const char* name : {"ladder_frame_tool", "smart_tool", "filter_tool"}) {
    config.tools.push_back(
        ToolConfig{name, std::string("rsp.tool_id.") + name, std::string("dock.slot.") + name, false});
  }
  config.mobile_platform =
      MobilePlatformConfig{std::move(topic), std::move(field), "station", "kit", milliseconds(1000)};
  return config;
}

void set_pose(RobotMoverState& mover, bool moving, const char* pose) {
  mover.moving = moving;
  std::strncpy(mover.actual_pose, pose, sizeof mover.actual_pose - 1);
}

// `T` is what the fake platform writes: RobotMoverState itself, or MirComState with it in `mover`.
template <class T>
class BridgePlatformCase {
 public:
  BridgePlatformCase(const char* topic, const char* field) : model_(config_with_platform(topic, field)) {}

  void run(RobotMoverState& (*mover_of)(T&)) {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    auto participant = dds::Participant::create(domain->config(), "station_bridge_platform_test");
    ASSERT_TRUE(participant) << participant.error().message;
    auto bridge = StationBridge::create(*participant, model_, spdlog::default_logger());
    ASSERT_TRUE(bridge) << bridge.error().message;
    auto platform_topic = dds::Topic<T>::create(*participant, model_.config().mobile_platform->state_topic);
    ASSERT_TRUE(platform_topic) << platform_topic.error().message;
    auto platform = dds::Writer<T>::create(*participant, *platform_topic);
    ASSERT_TRUE(platform) << platform.error().message;
    auto state_topic = dds::Topic<StationState>::create(*participant, kStationStateTopic);
    ASSERT_TRUE(state_topic) << state_topic.error().message;
    auto states = dds::Reader<StationState>::create(*participant, *state_topic);
    ASSERT_TRUE(states) << states.error().message;
    ASSERT_TRUE(platform->wait_for_readers(1, kDeliveryBound));
    ASSERT_TRUE(states->wait_for_writers(1, kDeliveryBound));

    const auto deadline = std::chrono::steady_clock::now() + kDeliveryBound;
    while (kit_.empty() && std::chrono::steady_clock::now() < deadline) {
      step(**bridge, *states);
      std::this_thread::sleep_for(milliseconds(5));
    }
    EXPECT_EQ(kit_, "unknown") << "the platform not heard yet";
    EXPECT_EQ(frame_, "away");

    T sample{};
    set_pose(mover_of(sample), false, "station");
    EXPECT_TRUE(until(**bridge, *platform, *states, sample, "at_station")) << "kit: " << kit_;
    EXPECT_EQ(frame_, "kit") << "the kit arrives with the ladder frame on it";

    set_pose(mover_of(sample), true, "");
    EXPECT_TRUE(until(**bridge, *platform, *states, sample, "away")) << "kit: " << kit_;
    EXPECT_EQ(frame_, "away") << "the frame on the kit leaves with it";
  }

 private:
  // One model step; keeps the last StationState's kit and ladder_frame.
  void step(StationBridge& bridge, dds::Reader<StationState>& states) {
    clock_.advance(kStep);
    bridge.step(clock_.now());
    while (true) {
      const Result<bool> taken = states.take_next(state_);
      if (!taken.is_ok() || !taken.value()) break;
      kit_ = state_->kit == nullptr ? "" : state_->kit;
      frame_ = state_->ladder_frame == nullptr ? "" : state_->ladder_frame;
    }
  }
  // Writes `sample` and steps until the StationState's kit is `kit`, or the wall-time bound.
  bool until(StationBridge& bridge, dds::Writer<T>& platform, dds::Reader<StationState>& states,
             const T& sample, const std::string& kit) {
    const auto deadline = std::chrono::steady_clock::now() + kDeliveryBound;
    while (std::chrono::steady_clock::now() < deadline) {
      EXPECT_TRUE(platform.write(sample).is_ok());
      step(bridge, states);
      if (kit_ == kit) return true;
      std::this_thread::sleep_for(milliseconds(5));
    }
    return false;
  }

  ManualClock clock_;
  StationModel model_;
  dds::Sample<StationState> state_;
  std::string kit_, frame_;
};

RobotMoverState& itself(RobotMoverState& state) {
  return state;
}
RobotMoverState& mover_field(MirComState& state) {
  return state.mover;
}

TEST(StationBridgePlatform, NodeTypeLayoutRobotMoverStateBringsAndTakesTheKit) {
  BridgePlatformCase<RobotMoverState>("/mir_com/mover/state", "").run(&itself);
}

TEST(StationBridgePlatform, HubLayoutMirComStateBringsAndTakesTheKit) {
  BridgePlatformCase<MirComState>("/mir_com/state", "mover").run(&mover_field);
}

}  // namespace
}  // namespace hubrt::sim::station
