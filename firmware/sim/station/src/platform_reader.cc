#include "platform_reader.h"

#include <cstring>
#include <string>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"

#include "mir_com_typed.h"  // registers RobotMoverState_ and MirComState_ as topic types

namespace hubrt::sim::station {
namespace {

// States are published at the hub's rate; more than this per model step is a flood, and the
// rest waits for the next step.
constexpr int kMaxTakesPerStep = 32;

// `T` is the State on the topic; `mover` picks the RobotMoverState out of it.
template <class T, const hub_msgs_msg_dds__RobotMoverState_& (*Mover)(const T&)>
class TypedPlatformReader final : public PlatformReader {
 public:
  TypedPlatformReader(dds::Topic<T> topic, dds::Reader<T> reader)
      : topic_(std::move(topic)), reader_(std::move(reader)) {}

  std::optional<PlatformReport> take() override {
    std::optional<PlatformReport> newest;
    for (int i = 0; i < kMaxTakesPerStep; ++i) {
      const Result<bool> taken = reader_.take_next(sample_);
      if (!taken.is_ok() || !taken.value()) break;
      const hub_msgs_msg_dds__RobotMoverState_& mover = Mover(sample_.get());
      // actual_pose is a bounded string<64>, a char array idlc sizes for the bound and its NUL;
      // strnlen keeps a peer's unterminated array from being read past its end.
      pose_.assign(mover.actual_pose, strnlen(mover.actual_pose, sizeof mover.actual_pose));
      newest = PlatformReport{mover.moving, pose_};
    }
    return newest;
  }

 private:
  dds::Topic<T> topic_;
  dds::Reader<T> reader_;
  dds::Sample<T> sample_;
  std::string pose_;
};

const hub_msgs_msg_dds__RobotMoverState_& itself(const hub_msgs_msg_dds__RobotMoverState_& state) {
  return state;
}
// MirComState has one RobotMoverState field, `mover` (station_config.cc checks the name).
const hub_msgs_msg_dds__RobotMoverState_& mover_of(const hub_msgs_msg_dds__MirComState_& state) {
  return state.mover;
}

template <class T, const hub_msgs_msg_dds__RobotMoverState_& (*Mover)(const T&)>
Expected<std::unique_ptr<PlatformReader>> make(const dds::Participant& participant,
                                               const std::string& topic_name) {
  auto topic = dds::Topic<T>::create(participant, topic_name);
  if (!topic) return std::move(topic).error();
  auto reader = dds::Reader<T>::create(participant, *topic);
  if (!reader) return std::move(reader).error();
  return std::unique_ptr<PlatformReader>(
      new TypedPlatformReader<T, Mover>(std::move(*topic), std::move(*reader)));
}

}  // namespace

Expected<std::unique_ptr<PlatformReader>> PlatformReader::create(const dds::Participant& participant,
                                                                 const MobilePlatformConfig& config) {
  if (config.field.empty()) {
    return make<hub_msgs_msg_dds__RobotMoverState_, &itself>(participant, config.state_topic);
  }
  return make<hub_msgs_msg_dds__MirComState_, &mover_of>(participant, config.state_topic);
}

}  // namespace hubrt::sim::station
