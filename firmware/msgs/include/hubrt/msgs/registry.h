// Finds message types by name: the DDS type name a topic announces, or the ROS 2 name a user
// types. Every message target (hubrt_add_messages) contributes its types to all_types().
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/msgs/type_info.h"

namespace hubrt::msgs {

// Not thread-safe while being filled; const member functions are safe to call concurrently once
// no more add() calls happen.
class TypeRegistry {
 public:
  // Adds every type of `types`, e.g. reflected::types_of_dock(). Adding a table that is already
  // there is a no-op. Fails (kInvalidArgument, naming both) when another table has the same DDS or
  // ROS name; the registry is then unchanged.
  Expected<void> add(std::span<const TypeInfo* const> types);

  // By DDS type name ("hub_msgs::msg::dds_::DockState_"), ROS 2 name ("hub_msgs/msg/DockState")
  // or the ROS 2 short form ("hub_msgs/DockState"). nullptr when unknown.
  [[nodiscard]] const TypeInfo* find(std::string_view name) const noexcept;
  [[nodiscard]] const TypeInfo* find_by_dds_name(std::string_view dds_name) const noexcept;
  [[nodiscard]] const TypeInfo* find_by_ros_name(std::string_view ros_name) const noexcept;

  // Every registered type, in registration order.
  [[nodiscard]] std::span<const TypeInfo* const> types() const noexcept { return types_; }

  // Up to `max` registered names (DDS or ROS) closest to `name`, closest first, for "did you
  // mean" messages; empty when nothing is close.
  [[nodiscard]] std::vector<std::string> suggest(std::string_view name, std::size_t max = 3) const;

  // "unknown message type 'X'" and then what helps: "; did you mean A, B?" when names are close,
  // else the packages this registry holds types of ("; this program holds hub_msgs/msg/*, ...").
  [[nodiscard]] std::string unknown_type_message(std::string_view name) const;

 private:
  std::vector<const TypeInfo*> types_;
  std::unordered_map<std::string_view, const TypeInfo*> by_dds_name_;
  std::unordered_map<std::string_view, const TypeInfo*> by_ros_name_;
};

}  // namespace hubrt::msgs
