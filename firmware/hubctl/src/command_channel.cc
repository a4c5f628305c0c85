#include "command_channel.h"

#include <fmt/format.h>

#include "hubrt/msgs/json.h"
#include "hubrt/msgs/set_field.h"

#include "command_qos.h"

namespace hubrt::hubctl {

void add_lifespan_option(CLI::App& cmd, std::uint32_t& lifespan_ms) {
  cmd.add_option(
         "--lifespan-ms", lifespan_ms,
         fmt::format("DDS LIFESPAN of the commands written, in ms (0: none; default {}, the hub file's "
                     "default command_timeout_ms: set the hub's own, which /diagnostics publishes). "
                     "Cyclone then drops a command that could no longer act instead of "
                     "retransmitting or delivering it late (docs/interop.md)",
                     kDefaultCommandLifespanMs))
      ->check(CLI::Range(0U, 3'600'000U));
}

Expected<PreparedCommand> prepare_command(const msgs::TypeInfo& type, const std::string& target_type,
                                          const std::string& target_name, const FieldAssignments& fields,
                                          std::string label) {
  if (type.descriptor == nullptr) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{} is not a topic type", type.dds_name));
  }
  dds::UntypedSample sample(*type.descriptor);
  for (const auto& [path, value] : {std::pair<std::string, std::string>{"target_type", target_type},
                                    std::pair<std::string, std::string>{"target_name", target_name}}) {
    if (auto set = msgs::set_field(type, sample.data(), path, value); !set) return std::move(set).error();
  }
  for (const auto& [path, value] : fields.fields) {
    if (auto set = msgs::set_field(type, sample.data(), path, value); !set) {
      return fields.error_at(path, set.error().message);
    }
  }
  // Unset strings are null in the sample; the wire wants "" (and the echo will say "").
  auto json = msgs::to_json(type, sample.data());
  if (auto filled = msgs::from_json(type, json, sample.data()); !filled) return std::move(filled).error();
  return PreparedCommand{std::move(label), std::move(sample), std::move(json)};
}

Expected<CommandChannel> CommandChannel::open(const dds::Participant& participant,
                                              const std::string& ros_topic, const msgs::TypeInfo& type) {
  if (type.descriptor == nullptr) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{} is not a topic type", type.dds_name));
  }
  auto topic = dds::UntypedTopic::create(participant, *type.descriptor, ros_topic);
  if (!topic) return std::move(topic).error();
  auto writer = dds::UntypedWriter::create(participant, *topic, command_writer_qos());
  if (!writer) return std::move(writer).error();
  return CommandChannel(std::move(*topic), std::move(*writer));
}

Expected<void> CommandChannel::wait_matched(double timeout_s) const {
  return writer_.wait_for_readers(1, std::chrono::nanoseconds(static_cast<std::int64_t>(timeout_s * 1e9)));
}

}  // namespace hubrt::hubctl
