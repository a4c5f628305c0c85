#include "field_path.h"

#include <gtest/gtest.h>

#include "dock.h"
#include "dock_reflect.h"

namespace hubrt::hubctl {
namespace {

TEST(FieldPath, LocatesNestedScalars) {
  const msgs::TypeInfo& type = msgs::type_info_of<hub_msgs_msg_dds__DockState_>();
  hub_msgs_msg_dds__DockState_ state{};
  state.header.seq = 77;
  state.fresh_msg = true;
  state.t_plus = 2.5f;
  const auto seq = locate(type, "header.seq");
  ASSERT_TRUE(seq.has_value());
  EXPECT_EQ(read_number(&state, *seq), 77.0);
  EXPECT_EQ(read_number(&state, *locate(type, "fresh_msg")), 1.0);
  EXPECT_EQ(read_number(&state, *locate(type, "t_plus")), 2.5);
}

TEST(FieldPath, UnknownOrNonScalarPaths) {
  const msgs::TypeInfo& type = msgs::type_info_of<hub_msgs_msg_dds__DockState_>();
  EXPECT_FALSE(locate(type, "header.nope").has_value());
  EXPECT_FALSE(locate(type, "name.x").has_value());
  hub_msgs_msg_dds__DockState_ state{};
  EXPECT_FALSE(read_number(&state, *locate(type, "name")).has_value());
}

}  // namespace
}  // namespace hubrt::hubctl
