// A Dock ECU written the ROS 1 way, in roscpp, for the ROS 1 benchmark: a 10 Hz state loop and an
// immediate echo from the command callback (the best a ROS 1 ECU does). Message types are not
// compiled in: DockState/DockCommand travel as topic_tools::ShapeShifter with the ROS 1 form of
// ros2/hub_msgs (firmware/ros1), the way hubbridge carries them.
//   hubrt_bench_ros1_ecu [--rate HZ]     (ROS_MASTER_URI says where the master is)
#include <mutex>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <ros/ros.h>
#include <ros/serialization.h>
#include <topic_tools/shape_shifter.h>

#include "hubrt/msgs/sample_memory.h"
#include "hubrt/ros1/codec.h"
#include "hubrt/ros1/definition.h"

#include "dock_reflect.h"
#include "dock_typed.h"

namespace {

struct RosType {
  std::string name, md5, definition;
};

RosType ros_type(const hubrt::ros1::Messages& messages, const std::string& name) {
  return {name, *hubrt::ros1::md5sum(messages, name), *hubrt::ros1::full_definition(messages, name)};
}

class Ecu {
 public:
  Ecu(ros::NodeHandle& node, const hubrt::ros1::Messages& messages)
      : state_type_(ros_type(messages, "hub_msgs/DockState")) {
    topic_tools::ShapeShifter shape;
    shape.morph(state_type_.md5, state_type_.name, state_type_.definition, "false");
    publisher_ = shape.advertise(node, "/dock_ecu/dock/state", 10);
    const RosType command = ros_type(messages, "hub_msgs/DockCommand");
    ros::SubscribeOptions options;
    options.initByFullCallbackType<const ros::MessageEvent<topic_tools::ShapeShifter const>&>(
        "/dock/command", 10,
        [this](const ros::MessageEvent<topic_tools::ShapeShifter const>& e) { on_command(e); });
    options.md5sum = command.md5;
    options.datatype = command.name;
    subscriber_ = node.subscribe(options);
    state_.set_name("dock");
    for (const char* slot : {"ladder_frame_tool", "filter_tool", "smart_tool", "spare"}) {
      state_.slots().append()->set_name(slot);
    }
  }

  void tick() {
    const std::lock_guard lock(mutex_);
    publish_locked();
  }

 private:
  void on_command(const ros::MessageEvent<topic_tools::ShapeShifter const>& event) {
    const auto& message = *event.getConstMessage();
    std::vector<std::uint8_t> bytes(message.size());
    ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
    message.write(stream);
    hub_msgs_msg_dds__DockCommand_ command{};
    const auto& type = hubrt::msgs::type_info_of<hub_msgs_msg_dds__DockCommand_>();
    if (hubrt::ros1::decode(type, bytes, &command)) return;
    const std::lock_guard lock(mutex_);
    const bool differs = std::string_view(command.action) != state_.echo().action();
    state_.wire().echo = command;
    state_.set_fresh_msg(true);
    if (differs) publish_locked();  // the immediate echo
  }

  void publish_locked() {
    const ros::WallTime now = ros::WallTime::now();
    state_.header().set_seq(++seq_);
    state_.header().stamp().set_sec(static_cast<std::int32_t>(now.sec));
    state_.header().stamp().set_nanosec(now.nsec);
    bytes_.clear();
    hubrt::ros1::encode(hubrt::msgs::type_info_of<hub_msgs_msg_dds__DockState_>(), &state_.wire(), bytes_);
    topic_tools::ShapeShifter shape;
    shape.morph(state_type_.md5, state_type_.name, state_type_.definition, "false");
    ros::serialization::IStream stream(bytes_.data(), static_cast<std::uint32_t>(bytes_.size()));
    shape.read(stream);
    publisher_.publish(shape);
  }

  RosType state_type_;
  ros::Publisher publisher_;
  ros::Subscriber subscriber_;
  std::mutex mutex_;
  hub_msgs::DockState state_;
  std::vector<std::uint8_t> bytes_;
  std::uint64_t seq_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  double rate_hz = 10.0;
  std::string msg_dir = HUBRT_SOURCE_DIR "/ros2";
  CLI::App app("roscpp Dock ECU for the ROS 1 benchmark");
  app.add_option("--rate", rate_hz, "State loop rate");
  app.add_option("--msg-dir", msg_dir, "ROS 2 interface tree");
  CLI11_PARSE(app, argc, argv);
  auto messages = hubrt::ros1::load_ros2_tree_as_ros1(msg_dir);
  if (!messages) {
    fmt::print(stderr, "{}\n", messages.error().message);
    return 2;
  }
  ros::init(argc, argv, "dock_ecu_roscpp", ros::init_options::NoRosout);
  ros::NodeHandle node;
  Ecu ecu(node, *messages);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  ros::WallRate rate(rate_hz);
  while (ros::ok()) {
    ecu.tick();
    rate.sleep();
  }
  return 0;
}
