// Where a node of a hub takes its commands and publishes its State, found by discovery, whatever
// the hub's layout (paper §5.4) — so that one scenario runs against either.
//
// The rule, from the endpoints of the hub's participant (hubd names its participant after the
// hub instance):
//   node-type layout  it writes a State topic ending in /<hub>/<node>/state, of type <X>State;
//                     its command topic is the one it reads with type <X>Command; the node type
//                     (the command's target_type) is that topic's second-last name.
//   hub layout        it writes a State topic ending in /<hub>/state whose type <H>State has a
//                     struct field <node>; its command topic is the one it reads with type
//                     <H>Command, which has the fragment <node>; the hub command's target_type
//                     is the hub type, <H> in snake case (ToolEcu -> tool_ecu).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/dds/discovery.h"
#include "hubrt/dds/participant.h"
#include "hubrt/msgs/registry.h"

namespace hubrt::hubctl {

enum class Layout : std::uint8_t { kNodeType, kHub };

struct NodeEndpoints {
  Layout layout = Layout::kNodeType;
  std::string command_topic;                     // ROS name
  const msgs::TypeInfo* command_type = nullptr;  // the topic's type (hub command in the hub layout)
  std::string state_topic;
  const msgs::TypeInfo* state_type = nullptr;
  // Hub layout: the node's field in the hub command and hub State. Empty in the node-type layout.
  std::string field;
  // The node's own command type (the fragment's type in the hub layout).
  const msgs::TypeInfo* node_command_type = nullptr;
  // Node-type layout: the node type; hub layout: the hub type.
  std::string target_type;
};

// Decides from one snapshot; nothing when the hub or the node is not (yet) seen, with the reason
// in `why` (what the hub's participant does publish, so a typo shows). `ros_namespace` ("" or
// "/cell_a"): only the hub's topics under it count — stations sharing one domain each run a hub of
// that name, every one under its station's namespace (docs/plant.md). Thread-safe.
std::optional<NodeEndpoints> locate_node(const dds::DiscoverySnapshot& snapshot,
                                         const msgs::TypeRegistry& types, std::string_view hub,
                                         std::string_view node, std::string& why,
                                         std::string_view ros_namespace = {});

// Polls discovery until the node is found. Errors: kNotFound after `timeout` with the reason.
Expected<NodeEndpoints> find_node(const dds::Participant& participant, const msgs::TypeRegistry& types,
                                  std::string_view hub, std::string_view node, Duration timeout,
                                  std::string_view ros_namespace = {});

// "ToolEcu" -> "tool_ecu". Thread-safe.
std::string snake_case(std::string_view camel);

}  // namespace hubrt::hubctl
