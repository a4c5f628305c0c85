#include "node_locator.h"

#include <algorithm>
#include <cctype>
#include <set>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hubrt/dds/ros_names.h"

namespace hubrt::hubctl {
namespace {

constexpr std::string_view kStateSuffix = "State_";
constexpr std::string_view kCommandSuffix = "Command_";

// "hub_msgs::msg::dds_::LiftState_" -> "hub_msgs::msg::dds_::LiftCommand_"; empty if not a State.
std::string command_type_name(std::string_view state_type) {
  if (!state_type.ends_with(kStateSuffix)) return {};
  return fmt::format("{}{}", state_type.substr(0, state_type.size() - kStateSuffix.size()), kCommandSuffix);
}

const msgs::FieldInfo* struct_field(const msgs::TypeInfo& type, std::string_view name) {
  for (const auto& field : type.fields) {
    if (field.name == name && field.kind == msgs::FieldKind::kStruct) return &field;
  }
  return nullptr;
}

// "/ns/lift/command" -> "lift".
std::string second_last_name(std::string_view topic) {
  const auto last = topic.rfind('/');
  if (last == std::string_view::npos || last == 0) return {};
  const auto before = topic.rfind('/', last - 1);
  return std::string(topic.substr(before == std::string_view::npos ? 0 : before + 1, last - before - 1));
}

struct Endpoint {
  std::string topic;  // ROS name
  std::string type;   // DDS name
};

}  // namespace

std::string snake_case(std::string_view camel) {
  std::string out;
  for (std::size_t i = 0; i < camel.size(); ++i) {
    const char c = camel[i];
    if (std::isupper(static_cast<unsigned char>(c)) != 0) {
      if (i > 0) out += '_';
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else {
      out += c;
    }
  }
  return out;
}

std::optional<NodeEndpoints> locate_node(const dds::DiscoverySnapshot& snapshot,
                                         const msgs::TypeRegistry& types, std::string_view hub,
                                         std::string_view node, std::string& why,
                                         std::string_view ros_namespace) {
  std::set<dds::Guid> keys;
  for (const auto& participant : snapshot.participants) {
    if (!participant.local && participant.name == hub) keys.insert(participant.key);
  }
  if (keys.empty()) {
    std::set<std::string> names;
    for (const auto& participant : snapshot.participants) {
      if (!participant.local && !participant.name.empty()) names.insert(participant.name);
    }
    why = fmt::format("no hub '{}' on the domain (participants seen: {})", hub,
                      names.empty() ? std::string("none") : fmt::format("{}", fmt::join(names, ", ")));
    return std::nullopt;
  }
  std::vector<Endpoint> writers;
  std::vector<Endpoint> readers;
  for (const auto& endpoint : snapshot.endpoints) {
    if (keys.count(endpoint.participant_key) == 0) continue;
    auto ros = dds::dds_to_ros_topic(endpoint.topic_name);
    if (!ros) continue;
    if (!ros_namespace.empty() && !(ros->starts_with(ros_namespace) && ros->size() > ros_namespace.size() &&
                                    (*ros)[ros_namespace.size()] == '/')) {
      continue;  // the same hub name in another station
    }
    (endpoint.direction == dds::EndpointDirection::kWriter ? writers : readers)
        .push_back(Endpoint{*ros, endpoint.type_name});
  }
  const auto reader_of_type = [&](std::string_view type) -> const Endpoint* {
    for (const auto& reader : readers) {
      if (reader.type == type) return &reader;
    }
    return nullptr;
  };

  const std::string node_state = fmt::format("/{}/{}/state", hub, node);
  const std::string hub_state = fmt::format("/{}/state", hub);
  for (const auto& writer : writers) {
    if (!writer.topic.ends_with(node_state)) continue;
    const msgs::TypeInfo* state_type = types.find_by_dds_name(writer.type);
    const Endpoint* command = reader_of_type(command_type_name(writer.type));
    const msgs::TypeInfo* command_type = command != nullptr ? types.find_by_dds_name(command->type) : nullptr;
    if (state_type == nullptr || command_type == nullptr) {
      why = fmt::format(
          "{} publishes {} ({}) but reads no command of the matching type {}, or hubctl does not "
          "know the types",
          hub, writer.topic, writer.type, command_type_name(writer.type));
      return std::nullopt;
    }
    NodeEndpoints out;
    out.layout = Layout::kNodeType;
    out.command_topic = command->topic;
    out.command_type = command_type;
    out.state_topic = writer.topic;
    out.state_type = state_type;
    out.node_command_type = command_type;
    out.target_type = second_last_name(command->topic);
    return out;
  }
  for (const auto& writer : writers) {
    if (!writer.topic.ends_with(hub_state)) continue;
    const msgs::TypeInfo* state_type = types.find_by_dds_name(writer.type);
    const Endpoint* command = reader_of_type(command_type_name(writer.type));
    const msgs::TypeInfo* command_type = command != nullptr ? types.find_by_dds_name(command->type) : nullptr;
    if (state_type == nullptr || command_type == nullptr) continue;
    const msgs::FieldInfo* state_field = struct_field(*state_type, node);
    const msgs::FieldInfo* command_field = struct_field(*command_type, node);
    if (state_field == nullptr || command_field == nullptr) {
      std::vector<std::string_view> nodes;
      for (std::size_t i = 7; i < state_type->fields.size(); ++i) nodes.push_back(state_type->fields[i].name);
      why = fmt::format("hub '{}' runs the hub layout ({}) and has no node '{}' (its nodes: {})", hub,
                        writer.topic, node, fmt::join(nodes, ", "));
      return std::nullopt;
    }
    NodeEndpoints out;
    out.layout = Layout::kHub;
    out.command_topic = command->topic;
    out.command_type = command_type;
    out.state_topic = writer.topic;
    out.state_type = state_type;
    out.field = std::string(node);
    out.node_command_type = command_field->nested;
    std::string_view stem = command_type->ros_name;
    stem = stem.substr(stem.rfind('/') + 1);
    stem.remove_suffix(std::string_view("Command").size());
    out.target_type = snake_case(stem);
    return out;
  }
  std::vector<std::string> published;
  published.reserve(writers.size());
  for (const auto& writer : writers) published.push_back(writer.topic);
  why = fmt::format(
      "hub '{}' publishes no State of a node '{}' (neither {} nor {} with a field '{}'); it "
      "publishes: {}",
      hub, node, node_state, hub_state, node, fmt::join(published, ", "));
  return std::nullopt;
}

Expected<NodeEndpoints> find_node(const dds::Participant& participant, const msgs::TypeRegistry& types,
                                  std::string_view hub, std::string_view node, Duration timeout,
                                  std::string_view ros_namespace) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::string why;
  for (;;) {
    auto snapshot = dds::discover(participant);
    if (!snapshot) return std::move(snapshot).error();
    if (auto found = locate_node(*snapshot, types, hub, node, why, ros_namespace)) return *found;
    if (std::chrono::steady_clock::now() >= deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return make_error(
      ErrorCode::kNotFound,
      fmt::format("{}/{}{}: {} (waited {:.1f} s)", hub, node,
                  ros_namespace.empty() ? std::string() : fmt::format(" under {}", ros_namespace), why,
                  to_seconds(timeout)));
}

}  // namespace hubrt::hubctl
