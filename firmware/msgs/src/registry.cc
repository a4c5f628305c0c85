#include "hubrt/msgs/registry.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "closest_names.h"

namespace hubrt::msgs {
namespace {

// "pkg/Type" -> "pkg/msg/Type", the short form `ros2 topic` accepts; anything else unchanged.
std::string expand_ros_short_name(std::string_view name) {
  const auto slash = name.find('/');
  if (slash == std::string_view::npos || name.find('/', slash + 1) != std::string_view::npos) return {};
  return fmt::format("{}/msg/{}", name.substr(0, slash), name.substr(slash + 1));
}

}  // namespace

Expected<void> TypeRegistry::add(std::span<const TypeInfo* const> types) {
  // Check everything first so that a failed add leaves the registry as it was.
  std::unordered_map<std::string_view, const TypeInfo*> pending;
  for (const TypeInfo* t : types) {
    for (const auto name : {t->dds_name, t->ros_name}) {
      if (name.empty()) continue;
      const TypeInfo* other = name == t->dds_name ? find_by_dds_name(name) : find_by_ros_name(name);
      if (other == nullptr) {
        const auto it = pending.find(name);
        other = it == pending.end() ? nullptr : it->second;
      }
      if (other != nullptr && other != t) {
        return make_error(
            ErrorCode::kInvalidArgument,
            fmt::format("two message types are named '{}': one from {} (C type {}), one from {} (C "
                        "type {})",
                        name, other->idl_file, other->c_name, t->idl_file, t->c_name));
      }
      pending.emplace(name, t);
    }
  }
  for (const TypeInfo* t : types) {
    if (by_dds_name_.contains(t->dds_name)) continue;
    types_.push_back(t);
    by_dds_name_.emplace(t->dds_name, t);
    if (!t->ros_name.empty()) by_ros_name_.emplace(t->ros_name, t);
  }
  return {};
}

const TypeInfo* TypeRegistry::find_by_dds_name(std::string_view dds_name) const noexcept {
  const auto it = by_dds_name_.find(dds_name);
  return it == by_dds_name_.end() ? nullptr : it->second;
}

const TypeInfo* TypeRegistry::find_by_ros_name(std::string_view ros_name) const noexcept {
  const auto it = by_ros_name_.find(ros_name);
  return it == by_ros_name_.end() ? nullptr : it->second;
}

const TypeInfo* TypeRegistry::find(std::string_view name) const noexcept {
  if (const TypeInfo* t = find_by_dds_name(name)) return t;
  if (const TypeInfo* t = find_by_ros_name(name)) return t;
  try {
    const std::string expanded = expand_ros_short_name(name);
    return expanded.empty() ? nullptr : find_by_ros_name(expanded);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}

std::vector<std::string> TypeRegistry::suggest(std::string_view name, std::size_t max) const {
  std::vector<std::string_view> names;
  for (const TypeInfo* t : types_) {
    names.push_back(t->dds_name);
    if (!t->ros_name.empty()) names.push_back(t->ros_name);
  }
  return detail::closest_names(name, names, max);
}

std::string TypeRegistry::unknown_type_message(std::string_view name) const {
  const std::vector<std::string> close = suggest(name);
  if (!close.empty())
    return fmt::format("unknown message type '{}'; did you mean {}?", name, fmt::join(close, ", "));
  // Nothing close: say what there is, by package ("hub_msgs/msg/*"), rather than an empty hint.
  std::vector<std::string> packages;
  for (const TypeInfo* t : types_) {
    const std::string_view ros = t->ros_name;
    const auto slash = ros.rfind('/');
    if (slash == std::string_view::npos) continue;
    std::string package = fmt::format("{}/*", ros.substr(0, slash));
    if (std::find(packages.begin(), packages.end(), package) == packages.end())
      packages.push_back(std::move(package));
  }
  if (packages.empty())
    return fmt::format("unknown message type '{}'; this program holds no message types", name);
  return fmt::format(
      "unknown message type '{}'; no type of this program has a similar name (it holds {} types: {})", name,
      types_.size(), fmt::join(packages, ", "));
}

}  // namespace hubrt::msgs
