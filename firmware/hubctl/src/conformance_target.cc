#include "conformance_target.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace hubrt::hubctl {
namespace {

const msgs::FieldInfo* field(const msgs::TypeInfo& type, std::string_view name) noexcept {
  for (const msgs::FieldInfo& f : type.fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

std::vector<std::string_view> split(std::string_view text) {
  std::vector<std::string_view> parts;
  while (!text.empty()) {
    const auto slash = text.find('/');
    const std::string_view part = text.substr(0, slash);
    if (!part.empty()) parts.push_back(part);
    if (slash == std::string_view::npos) break;
    text = text.substr(slash + 1);
  }
  return parts;
}

}  // namespace

bool is_state_type(const msgs::TypeInfo& type) noexcept {
  const msgs::FieldInfo* echo = field(type, "echo");
  return echo != nullptr && echo->kind == msgs::FieldKind::kStruct && field(type, "fresh_msg") != nullptr;
}

bool is_hub_state_topic(std::string_view ros_topic) noexcept {
  return !ros_topic.starts_with("/sim/");
}

bool is_hub_state_type(const msgs::TypeInfo& type) noexcept {
  if (!is_state_type(type)) return false;
  for (const msgs::FieldInfo& f : type.fields) {
    if (f.kind == msgs::FieldKind::kStruct && f.nested != nullptr && f.name != "echo" &&
        is_state_type(*f.nested))
      return true;
  }
  return false;
}

Expected<StateTopicParts> split_state_topic(std::string_view topic, TargetLayout layout) {
  const std::vector<std::string_view> parts = split(topic);
  const std::size_t needed = layout == TargetLayout::kNodeType ? 3 : 2;
  if (parts.size() < needed || parts.back() != "state") {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("'{}' is not a {} State topic ({})", topic,
                                  layout == TargetLayout::kNodeType ? "node" : "hub",
                                  layout == TargetLayout::kNodeType ? "<namespace>/<hub>/<node>/state"
                                                                    : "<namespace>/<hub>/state"));
  }
  StateTopicParts out;
  const std::size_t hub_index = parts.size() - needed;
  out.hub_name = std::string(parts[hub_index]);
  if (layout == TargetLayout::kNodeType) out.node_name = std::string(parts[hub_index + 1]);
  for (std::size_t i = 0; i < hub_index; ++i) out.ros_namespace += fmt::format("/{}", parts[i]);
  return out;
}

Expected<void> ProfileBook::add_file(const std::string& path) {
  auto profile = load_profile(path);
  if (!profile) return std::move(profile).error();
  given_.push_back(profile->hub_type);
  profiles_.insert_or_assign(profile->hub_type, std::move(*profile));
  return {};
}

const ConformanceProfile* ProfileBook::find(const std::string& hub_type, std::string& why) {
  if (const auto it = profiles_.find(hub_type); it != profiles_.end()) return &it->second;
  if (const auto it = missing_.find(hub_type); it != missing_.end()) {
    why = it->second;
    return nullptr;
  }
  auto profile = find_profile(hub_type);
  if (!profile) {
    why = profile.error().message;
    missing_.emplace(hub_type, why);
    return nullptr;
  }
  return &profiles_.emplace(hub_type, std::move(*profile)).first->second;
}

const ConformanceProfile* ProfileBook::only_given() const noexcept {
  if (given_.size() != 1) return nullptr;
  const auto it = profiles_.find(given_.front());
  return it == profiles_.end() ? nullptr : &it->second;
}

Target resolve_target(const std::string& state_topic, const msgs::TypeInfo& state_type,
                      const DiagnosticsByHub& diagnostics, ProfileBook& profiles,
                      const TargetOverrides& overrides) {
  Target t;
  t.state_topic = state_topic;
  t.state_type = &state_type;
  t.layout = is_hub_state_type(state_type) ? TargetLayout::kHub : TargetLayout::kNodeType;
  if (const msgs::FieldInfo* echo = field(state_type, "echo"); echo != nullptr) t.command_type = echo->nested;
  if (t.command_type == nullptr || t.command_type->descriptor == nullptr) {
    t.command_problems.push_back(
        fmt::format("{}: the type of its echo is not a command topic type", state_topic));
  }
  auto parts = split_state_topic(state_topic, t.layout);
  if (!parts) {
    t.command_problems.push_back(parts.error().message);
    return t;
  }
  t.ros_namespace = parts->ros_namespace;
  t.hub_name = parts->hub_name;
  t.node_name = parts->node_name;

  const auto diag = diagnostics.find(t.hub_name);
  const HubDiagnostics* heard = diag == diagnostics.end() ? nullptr : &diag->second;
  if (!overrides.hub_type.empty()) {
    t.hub_type = overrides.hub_type;
  } else if (heard != nullptr && !heard->hub_type.empty()) {
    t.hub_type = heard->hub_type;
  } else if (const ConformanceProfile* only = profiles.only_given(); only != nullptr) {
    t.hub_type = only->hub_type;
  }
  std::string why_no_profile;
  if (!t.hub_type.empty()) {
    t.profile = profiles.find(t.hub_type, why_no_profile);
  } else {
    why_no_profile = fmt::format(
        "the type of hub '{}' is unknown: it publishes no /diagnostics; give --hub-type "
        "or --profile",
        t.hub_name);
  }

  const std::string profile_source = t.profile != nullptr ? fmt::format("profile {}", t.profile->file) : "";
  if (overrides.rate_hz) {
    t.period_s = 1.0 / *overrides.rate_hz;
    t.period_source = "--rate";
  } else if (heard != nullptr && heard->period_ms && *heard->period_ms > 0) {
    t.period_s = *heard->period_ms / 1e3;
    t.period_source = "/diagnostics";
  } else if (t.profile != nullptr && t.profile->rate_hz) {
    t.period_s = 1.0 / *t.profile->rate_hz;
    t.period_source = profile_source;
  }
  if (overrides.command_timeout_ms) {
    t.timeout_s = *overrides.command_timeout_ms / 1e3;
    t.timeout_source = "--command-timeout";
  } else if (heard != nullptr && heard->command_timeout_ms && *heard->command_timeout_ms > 0) {
    t.timeout_s = *heard->command_timeout_ms / 1e3;
    t.timeout_source = "/diagnostics";
  } else if (t.profile != nullptr && t.profile->command_timeout_ms) {
    t.timeout_s = *t.profile->command_timeout_ms / 1e3;
    t.timeout_source = profile_source;
  }
  if (heard != nullptr && heard->immediate_state_interval_ms && *heard->immediate_state_interval_ms >= 0)
    t.immediate_interval_s = *heard->immediate_state_interval_ms / 1e3;
  if (t.timeout_s <= 0) {
    t.command_problems.push_back(
        "the command timeout is unknown: the hub does not publish it on /diagnostics; "
        "give --command-timeout");
  }

  if (t.layout == TargetLayout::kNodeType) {
    if (heard != nullptr) {
      if (const auto it = heard->node_types.find(t.node_name); it != heard->node_types.end())
        t.node_type = it->second;
    }
    if (t.node_type.empty() && t.profile != nullptr && t.command_type != nullptr) {
      t.node_type = t.profile->node_type_of_command(t.command_type->ros_name).value_or("");
    }
    if (t.node_type.empty()) {
      t.command_problems.push_back(
          fmt::format("the node type of '{}' is unknown: neither /diagnostics nor a "
                      "profile's command_type tells it",
                      t.node_name));
    } else {
      t.command_topic = fmt::format("{}/{}/command", t.ros_namespace, t.node_type);
      t.target_type = t.node_type;
      t.target_name = t.node_name;
    }
  } else {
    t.command_topic = fmt::format("{}/{}/command", t.ros_namespace, t.hub_name);
    t.target_type = t.hub_type;
    t.target_name = t.hub_name;
    if (t.hub_type.empty()) t.command_problems.push_back(why_no_profile);
  }

  if (t.profile == nullptr) {
    t.command_problems.push_back(why_no_profile);
  } else if (t.layout == TargetLayout::kHub) {
    if (t.profile->hub_layout) {
      t.commands = &*t.profile->hub_layout;
    } else {
      t.command_problems.push_back(fmt::format("{} has no hub_layout section", t.profile->file));
    }
  } else if (!t.node_type.empty()) {
    t.commands = t.profile->for_node_type(t.node_type);
    if (t.commands == nullptr) {
      t.command_problems.push_back(fmt::format("{} lists no node type '{}'", t.profile->file, t.node_type));
    }
  }
  if (!t.command_problems.empty()) t.commands = nullptr;
  return t;
}

}  // namespace hubrt::hubctl
