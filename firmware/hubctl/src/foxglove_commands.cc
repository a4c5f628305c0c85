#include "foxglove_commands.h"

#include <optional>

#include <fmt/format.h>

#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/all_types.h"

#include "command_qos.h"
#include "tap_selection.h"

namespace hubrt::hubctl::foxglove {

struct DdsCommandWriters::Writer final : CommandWriter {
  dds::UntypedTopic topic;
  dds::UntypedWriter writer;
  Writer(dds::UntypedTopic t, dds::UntypedWriter w) : topic(std::move(t)), writer(std::move(w)) {}
  Status write(std::span<const std::uint8_t> cdr) noexcept override { return writer.write_serialized(cdr); }
};

DdsCommandWriters::DdsCommandWriters(const dds::Participant& participant, std::size_t max_topics)
    : participant_(&participant), max_topics_(max_topics) {}

Expected<std::shared_ptr<CommandWriter>> DdsCommandWriters::open(const std::string& topic,
                                                                 std::string_view schema_name) {
  // Foxglove names a ROS 2 type as the channel's schemaName said ("pkg/msg/Type"); "pkg/Type" too.
  std::string ros_name(schema_name);
  if (const auto slash = ros_name.find('/');
      slash != std::string::npos && ros_name.find('/', slash + 1) == std::string::npos)
    ros_name.insert(slash, "/msg");
  const msgs::TypeInfo* type = msgs::all_types().find_by_ros_name(ros_name);
  if (type == nullptr || type->descriptor == nullptr || !is_command_type(*type))
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("schemaName \"{}\" is no command type of this station (hub_msgs/msg/...Command)",
                    schema_name));
  const std::lock_guard lock(mutex_);
  std::erase_if(writers_, [](const auto& entry) { return entry.second.expired(); });
  if (auto known = writers_.find(topic); known != writers_.end()) {
    auto writer = known->second.lock();
    if (writer->topic.descriptor().m_typename != std::string_view(type->descriptor->m_typename))
      return make_error(ErrorCode::kInvalidArgument, fmt::format("{} is written as {} already", topic,
                                                                 writer->topic.descriptor().m_typename));
    return std::shared_ptr<CommandWriter>(writer);
  }
  if (writers_.size() >= max_topics_)
    return make_error(ErrorCode::kOutOfRange,
                      fmt::format("at most {} command topics at a time", max_topics_));
  auto dds_topic = dds::UntypedTopic::create(*participant_, *type->descriptor, topic);
  if (!dds_topic) return std::move(dds_topic).error();
  auto writer = dds::UntypedWriter::create(*participant_, *dds_topic, command_writer_qos());
  if (!writer) return std::move(writer).error();
  auto shared = std::make_shared<Writer>(std::move(*dds_topic), std::move(*writer));
  writers_[topic] = shared;
  return std::shared_ptr<CommandWriter>(std::move(shared));
}

}  // namespace hubrt::hubctl::foxglove
