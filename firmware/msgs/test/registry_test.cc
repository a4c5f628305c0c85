#include "hubrt/msgs/registry.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hubrt/msgs/all_types.h"

#include "dock_reflect.h"
#include "reflect_test_types_reflect.h"

namespace hubrt::msgs {
namespace {

using ::testing::HasSubstr;

TEST(AllTypes, HoldsTheCommonAndTheDockTypesButNoTestTypes) {
  const TypeRegistry& reg = all_types();
  for (const char* name :
       {"builtin_interfaces::msg::dds_::Time_", "std_msgs::msg::dds_::Header_",
        "diagnostic_msgs::msg::dds_::KeyValue_", "diagnostic_msgs::msg::dds_::DiagnosticStatus_",
        "diagnostic_msgs::msg::dds_::DiagnosticArray_", "hub_msgs::msg::dds_::StateHeader_",
        "hub_msgs::msg::dds_::DockCommand_", "hub_msgs::msg::dds_::DockSlot_",
        "hub_msgs::msg::dds_::DockState_"}) {
    EXPECT_NE(reg.find_by_dds_name(name), nullptr) << name;
  }
  EXPECT_EQ(reg.find("hubrt_test::msg::dds_::AllKinds_"), nullptr) << "NO_REGISTRY types must stay out";
  EXPECT_EQ(&all_types(), &reg) << "one registry per program";
}

TEST(AllTypes, FindsByDdsRosAndShortRosName) {
  const TypeInfo* state = &type_info_of<hub_msgs_msg_dds__DockState_>();
  EXPECT_EQ(all_types().find("hub_msgs::msg::dds_::DockState_"), state);
  EXPECT_EQ(all_types().find("hub_msgs/msg/DockState"), state);
  EXPECT_EQ(all_types().find("hub_msgs/DockState"), state);
  EXPECT_EQ(all_types().find_by_ros_name("hub_msgs/msg/DockState"), state);
  EXPECT_EQ(all_types().find_by_dds_name("hub_msgs/msg/DockState"), nullptr);
  EXPECT_EQ(all_types().find("hub_msgs/msg/DockStat"), nullptr);
  EXPECT_EQ(all_types().find("DockState"), nullptr);
  EXPECT_EQ(all_types().find("a/b/c/d"), nullptr);
}

TEST(AllTypes, SuggestsCloseNames) {
  EXPECT_THAT(all_types().suggest("hub_msgs/msg/DockStat"), ::testing::Contains("hub_msgs/msg/DockState"));
  EXPECT_TRUE(all_types().suggest("completely/unrelated/Thing").empty());
}

// Issue 34: with nothing close the error ended in an empty "did you mean:".
TEST(TypeRegistry, UnknownTypeMessageSaysWhatThereIsWhenNothingIsClose) {
  TypeRegistry reg;
  ASSERT_TRUE(reg.add(reflected::types_of_dock()));
  EXPECT_THAT(reg.unknown_type_message("hub_msgs/msg/DockStat"),
              ::testing::StartsWith("unknown message type 'hub_msgs/msg/DockStat'; did you mean "));
  EXPECT_THAT(reg.unknown_type_message("hub_msgs/msg/DockStat"), ::testing::EndsWith("?"));
  const std::string far = reg.unknown_type_message("completely/unrelated/Thing");
  EXPECT_EQ(
      far,
      "unknown message type 'completely/unrelated/Thing'; no type of this program has a similar name (it "
      "holds 3 types: hub_msgs/msg/*)");
  EXPECT_THAT(far, ::testing::Not(::testing::HasSubstr("did you mean")));
  EXPECT_EQ(TypeRegistry().unknown_type_message("x/y"),
            "unknown message type 'x/y'; this program holds no message types");
}

TEST(TypeRegistry, AddingTheSameListTwiceAddsNothing) {
  TypeRegistry reg;
  ASSERT_TRUE(reg.add(reflected::types_of_dock()));
  ASSERT_TRUE(reg.add(reflected::types_of_dock()));
  EXPECT_EQ(reg.types().size(), 3u);
  EXPECT_EQ(reg.types()[2], &type_info_of<hub_msgs_msg_dds__DockState_>());
}

TEST(TypeRegistry, RefusesADifferentTableWithATakenNameAndStaysUnchanged) {
  TypeRegistry reg;
  ASSERT_TRUE(reg.add(reflected::types_of_dock()));
  const TypeInfo& real = type_info_of<hub_msgs_msg_dds__DockSlot_>();
  const TypeInfo impostor{real.dds_name, "", "impostor_c_name", "other.idl", real.size, nullptr, real.fields};
  const TypeInfo fresh{"fresh::Type", "", "fresh_Type", "other.idl", real.size, nullptr, real.fields};
  const TypeInfo* list[] = {&fresh, &impostor};
  const auto added = reg.add(list);
  ASSERT_FALSE(added);
  EXPECT_EQ(added.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(added.error().message, HasSubstr("'hub_msgs::msg::dds_::DockSlot_'"));
  EXPECT_THAT(added.error().message, HasSubstr("dock.idl"));
  EXPECT_THAT(added.error().message, HasSubstr("impostor_c_name"));
  EXPECT_EQ(reg.find("fresh::Type"), nullptr) << "a failed add must not add part of the list";
  EXPECT_EQ(reg.types().size(), 3u);
}

TEST(TypeRegistry, TypesWithoutRosNameAreFoundByDdsNameOnly) {
  TypeRegistry reg;
  ASSERT_TRUE(reg.add(reflected::types_of_reflect_test_types()));
  EXPECT_EQ(reg.find("plain::Point"), &type_info_of<plain_Point>());
  EXPECT_EQ(reg.find("hubrt_test/AllKinds"), &type_info_of<hubrt_test_msg_dds__AllKinds_>());
}

}  // namespace
}  // namespace hubrt::msgs
