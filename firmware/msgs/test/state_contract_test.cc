// The wire contract (DESIGN.md §3) for every hub message type in the registry, including those
// that hubs add later: a State starts with the common fields in order, a Command with its address.
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/msgs/all_types.h"

namespace hubrt::msgs {
namespace {

struct FieldExpectation {
  std::string_view name;
  std::string_view type;  // describe_type()
};

bool is_hub_type_ending_with(const TypeInfo& t, std::string_view suffix) {
  return t.ros_name.starts_with("hub_msgs/msg/") && t.ros_name.ends_with(suffix);
}

void expect_prefix(const TypeInfo& t, const std::vector<FieldExpectation>& prefix) {
  SCOPED_TRACE(std::string(t.ros_name));
  ASSERT_GE(t.fields.size(), prefix.size());
  for (std::size_t i = 0; i < prefix.size(); ++i) {
    EXPECT_EQ(t.fields[i].name, prefix[i].name) << "field " << i + 1;
    if (!prefix[i].type.empty()) {
      EXPECT_EQ(describe_type(t.fields[i]), prefix[i].type) << prefix[i].name;
    }
  }
}

TEST(StateContract, EveryStateStartsWithTheCommonFieldsInOrder) {
  int states = 0;
  for (const TypeInfo* t : all_types().types()) {
    if (!is_hub_type_ending_with(*t, "State")) continue;
    ++states;
    // Hub States are bounded (issue 11: error_list as runtime::ErrorList holds it); the simulated
    // station's (firmware/sim/msg/StationState.msg, not a hub) is not.
    const bool hub = t->idl_file != "station.idl";
    expect_prefix(*t, {{"header", "hub_msgs/msg/StateHeader"},
                       {"name", hub ? "string<64>" : "string"},
                       {"echo", ""},
                       {"fresh_msg", "bool"},
                       {"t_plus", "float32"},
                       {"got_reset", "bool"},
                       {"error_list", hub ? "sequence<string<191>, 16>" : "sequence<string>"}});
    // echo is the node's own Command type, verbatim.
    ASSERT_NE(t->fields[2].nested, nullptr);
    const std::string command =
        std::string(t->ros_name.substr(0, t->ros_name.size() - std::string_view("State").size())) + "Command";
    EXPECT_EQ(t->fields[2].nested->ros_name, command);
  }
  EXPECT_GE(states, 1) << "no hub State type registered (is hubrt_msgs_dock linked into hubrt_msgs_all?)";
}

TEST(StateContract, EveryCommandStartsWithItsAddressAndAction) {
  int commands = 0;
  for (const TypeInfo* t : all_types().types()) {
    if (!is_hub_type_ending_with(*t, "Command")) continue;
    ++commands;
    // Hub commands are bounded at runtime::kMaxCommandString (64); the station's is not a hub's.
    const std::string_view text = t->idl_file != "station.idl" ? "string<64>" : "string";
    expect_prefix(*t, {{"target_type", text}, {"target_name", text}, {"action", text}});
  }
  EXPECT_GE(commands, 1);
}

}  // namespace
}  // namespace hubrt::msgs
