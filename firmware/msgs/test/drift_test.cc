// The drift check can fail, and says precisely why: deliberately drifted .msg text against the
// real reflected IDL types.
#include "hubrt/msgs/drift.h"

#include <algorithm>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "builtin_interfaces_reflect.h"
#include "diagnostic_msgs_reflect.h"
#include "dock_reflect.h"
#include "hub_msgs_common_reflect.h"
#include "reflect_test_types_reflect.h"

namespace hubrt::msgs {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr const char* kDockState =
    "StateHeader header\n"
    "string<=64 name\n"
    "DockCommand echo\n"
    "bool fresh_msg\n"
    "float32 t_plus\n"
    "bool got_reset\n"
    "string<=191[<=16] error_list\n"
    "DockSlot[<=16] slots\n";

constexpr const char* kWhere =
    "hub_msgs/msg/DockState (DockState.msg vs IDL hub_msgs::msg::dds_::DockState_ in dock.idl): ";

ros::MsgSpec msg(const std::string& package, const std::string& name, const std::string& text) {
  auto spec = ros::parse_msg(text, package, name, name + ".msg");
  EXPECT_TRUE(spec) << spec.error().message;
  return spec ? *spec : ros::MsgSpec{};
}

// The .msg files of the common and the dock types, with DockState given as `dock_state`.
std::vector<ros::MsgSpec> package_with_dock_state(const std::string& dock_state) {
  return {
      msg("builtin_interfaces", "Time", "int32 sec\nuint32 nanosec\n"),
      msg("std_msgs", "Header", "builtin_interfaces/Time stamp\nstring frame_id\n"),
      msg("diagnostic_msgs", "KeyValue", "string key\nstring value\n"),
      msg("diagnostic_msgs", "DiagnosticStatus",
          "byte OK=0\nbyte level\nstring name\nstring message\nstring hardware_id\nKeyValue[] values\n"),
      msg("diagnostic_msgs", "DiagnosticArray", "std_msgs/Header header\nDiagnosticStatus[] status\n"),
      msg("hub_msgs", "StateHeader", "builtin_interfaces/Time stamp\nuint64 seq\nuint8 lifecycle\n"),
      msg("hub_msgs", "DockCommand", "string<=64 target_type\nstring<=64 target_name\nstring<=64 action\n"),
      msg("hub_msgs", "DockSlot", "string<=64 name\nbool occupied\n"),
      msg("hub_msgs", "DockState", dock_state),
  };
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

// The common and the dock types only, so that hubs added later do not change these cases (the
// check over every registered type is idl_mapping_test.cc).
std::vector<std::string> drift(const std::vector<ros::MsgSpec>& msgs) {
  std::vector<const TypeInfo*> types;
  for (const auto list : {reflected::types_of_builtin_interfaces(), reflected::types_of_diagnostic_msgs(),
                          reflected::types_of_hub_msgs_common(), reflected::types_of_dock()}) {
    types.insert(types.end(), list.begin(), list.end());
  }
  return find_drift(msgs, types);
}

TEST(FindDrift, TheMatchingPackageHasNone) {
  EXPECT_THAT(drift(package_with_dock_state(kDockState)), ElementsAre());
}

TEST(FindDrift, RenamedField) {
  EXPECT_THAT(drift(package_with_dock_state(replace(kDockState, "bool fresh_msg", "bool fresh"))),
              ElementsAre(std::string(kWhere) +
                          "field 4 is named 'fresh' in the .msg (line 4) but 'fresh_msg' in the IDL"));
}

TEST(FindDrift, ChangedPrimitiveType) {
  EXPECT_THAT(drift(package_with_dock_state(replace(kDockState, "float32 t_plus", "float64 t_plus"))),
              ElementsAre(std::string(kWhere) +
                          "field 5 't_plus' (line 5) is float64 in the .msg but float32 in the IDL"));
}

TEST(FindDrift, SequenceVersusSingleValue) {
  EXPECT_THAT(
      drift(package_with_dock_state(
          replace(kDockState, "string<=191[<=16] error_list", "string<=191 error_list"))),
      ElementsAre(
          std::string(kWhere) +
          "field 7 'error_list' (line 7) is string<=191 in the .msg but string<=191[<=16] in the IDL: a "
          "single value in the .msg, a bounded sequence in the IDL"));
  EXPECT_THAT(
      drift(package_with_dock_state(replace(kDockState, "DockSlot[<=16] slots", "DockSlot[4] slots"))),
      ElementsAre(HasSubstr("is hub_msgs/DockSlot[4] in the .msg but hub_msgs/DockSlot[<=16] in the IDL: a "
                            "fixed-size array in the .msg, a bounded sequence in the IDL")));
}

TEST(FindDrift, BoundedStringVersusUnbounded) {
  EXPECT_THAT(drift(package_with_dock_state(replace(kDockState, "string<=64 name", "string<=16 name"))),
              ElementsAre(std::string(kWhere) +
                          "field 2 'name' (line 2) is string<=16 in the .msg but string<=64 in the IDL"));
  EXPECT_THAT(drift(package_with_dock_state(replace(kDockState, "string<=64 name", "string name"))),
              ElementsAre(std::string(kWhere) +
                          "field 2 'name' (line 2) is string in the .msg but string<=64 in the IDL"));
}

TEST(FindDrift, NestedTypeNamesIncludingTheBuiltinTimeMapping) {
  EXPECT_THAT(
      drift(package_with_dock_state(replace(kDockState, "DockCommand echo", "DockSlot echo"))),
      ElementsAre(std::string(kWhere) +
                  "field 3 'echo' (line 3) is hub_msgs/DockSlot in the .msg but hub_msgs/DockCommand in the "
                  "IDL (IDL type hub_msgs::msg::dds_::DockCommand_)"));
  auto msgs = package_with_dock_state(kDockState);
  msgs[5] =
      msg("hub_msgs", "StateHeader", "builtin_interfaces/Duration stamp\nuint64 seq\nuint8 lifecycle\n");
  EXPECT_THAT(drift(msgs),
              ElementsAre("hub_msgs/msg/StateHeader (StateHeader.msg vs IDL "
                          "hub_msgs::msg::dds_::StateHeader_ in hub_msgs_common.idl): field 1 'stamp' "
                          "(line 1) is builtin_interfaces/Duration in the .msg but builtin_interfaces/Time "
                          "in the IDL (IDL type builtin_interfaces::msg::dds_::Time_)"));
}

TEST(FindDrift, TypeOnOneSideOnly) {
  auto msgs = package_with_dock_state(kDockState);
  msgs.erase(std::find_if(msgs.begin(), msgs.end(), [](const auto& m) { return m.name == "DockSlot"; }));
  msgs.push_back(msg("hub_msgs", "DockLight", "bool on\n"));
  EXPECT_THAT(
      drift(msgs),
      ElementsAre("hub_msgs/msg/DockSlot is in the IDL (hub_msgs::msg::dds_::DockSlot_ in dock.idl) but "
                  "hub_msgs/msg/DockSlot.msg does not exist",
                  "DockLight.msg defines hub_msgs/msg/DockLight, but no IDL type "
                  "hub_msgs::msg::dds_::DockLight_ exists (no hubrt_add_messages() target declares it)"));
}

TEST(FindDrift, MissingAndExtraFields) {
  EXPECT_THAT(drift(package_with_dock_state(replace(kDockState, "DockSlot[<=16] slots\n", ""))),
              ElementsAre(std::string(kWhere) +
                          "IDL field 8 'slots' (hub_msgs/DockSlot[<=16]) is missing from the .msg"));
  EXPECT_THAT(drift(package_with_dock_state(std::string(kDockState) + "uint8 battery\n")),
              ElementsAre(std::string(kWhere) + ".msg field 9 'battery' (uint8, line 9) is not in the IDL"));
}

TEST(FindDrift, SwappedFieldsNameTheOrder) {
  const std::string swapped = replace(replace(kDockState, "bool fresh_msg\n", ""), "bool got_reset\n",
                                      "bool got_reset\nbool fresh_msg\n");
  const auto found = drift(package_with_dock_state(swapped));
  ASSERT_FALSE(found.empty());
  EXPECT_THAT(found[0],
              HasSubstr("field 4 is named 't_plus' in the .msg (line 4) but 'fresh_msg' in the IDL (the IDL "
                        "has 't_plus' as field 5: order differs)"));
}

TEST(FindDrift, PackageWithoutAnyMsg) {
  auto msgs = package_with_dock_state(kDockState);
  std::erase_if(msgs, [](const auto& m) { return m.package == "diagnostic_msgs"; });
  const auto found = drift(msgs);
  ASSERT_EQ(found.size(), 3u);
  EXPECT_EQ(found[0],
            "diagnostic_msgs/msg/DiagnosticArray (IDL diagnostic_msgs::msg::dds_::DiagnosticArray_ in "
            "diagnostic_msgs.idl) has no .msg: there is no ROS 2 package 'diagnostic_msgs' with a "
            "diagnostic_msgs/msg/DiagnosticArray.msg");
}

// Every kind the tables know maps to its .msg spelling (byte for octet, char as uint8, arrays,
// bounded sequences, typedef'd sequences, legacy IDL integer names).
TEST(FindDrift, EveryKindMatchesItsMsgSpelling) {
  const std::vector<ros::MsgSpec> msgs = {
      msg("hubrt_test", "Inner", "string label\nint32[3] values\n"),
      msg("hubrt_test", "AllKinds",
          "bool flag\nbyte raw\nint8 i8\nchar u8\nint16 i16\nuint16 u16\nint32 i32\nuint32 u32\nint64 i64\n"
          "uint64 u64\nint16 legacy_short\nuint32 legacy_ulong\nfloat32 f32\nfloat64 f64\nstring text\n"
          "builtin_interfaces/Time stamp\nInner inner\nint32[] ints\nstring[] words\nInner[] inners\n"
          "byte[<=4] bounded_bytes\nint16[] aliased\nfloat64[4] matrix\nstring[2] names\nInner[2] pair\n"),
      msg("builtin_interfaces", "Time", "int32 sec\nuint32 nanosec\n"),
  };
  const TypeInfo* types[] = {&type_info_of<hubrt_test_msg_dds__Inner_>(),
                             &type_info_of<hubrt_test_msg_dds__AllKinds_>(),
                             &type_info_of<builtin_interfaces_msg_dds__Time_>()};
  EXPECT_THAT(find_drift(msgs, types), ElementsAre());
}

// Bounds are part of the type: a .msg that drops or changes one drifts (issue 11: the IDL bounds
// are what Cyclone enforces, so a ROS 2 peer built from the .msg must know them).
TEST(FindDrift, StringAndSequenceBoundsMustMatch) {
  constexpr const char* kBounded =
      "string<=8 label\nuint32 count\nSlot first\nstring<=6[<=3] notes\nSlot[<=4] slots\nint32[<=2] "
      "numbers\n";
  const auto with = [](const std::string& bounded) {
    return std::vector<ros::MsgSpec>{msg("hubrt_test", "Slot", "string<=8 name\nbool occupied\n"),
                                     msg("hubrt_test", "Bounded", bounded)};
  };
  const TypeInfo* types[] = {&type_info_of<hubrt_test_msg_dds__Slot_>(),
                             &type_info_of<hubrt_test_msg_dds__Bounded_>()};
  EXPECT_THAT(find_drift(with(kBounded), types), ElementsAre());
  const std::string where =
      "hubrt_test/msg/Bounded (Bounded.msg vs IDL hubrt_test::msg::dds_::Bounded_ in "
      "reflect_test_types.idl): ";
  EXPECT_THAT(find_drift(with(replace(kBounded, "string<=8 label", "string label")), types),
              ElementsAre(where + "field 1 'label' (line 1) is string in the .msg but string<=8 in the IDL"));
  EXPECT_THAT(
      find_drift(with(replace(kBounded, "string<=8 label", "string<=9 label")), types),
      ElementsAre(where + "field 1 'label' (line 1) is string<=9 in the .msg but string<=8 in the IDL"));
  EXPECT_THAT(
      find_drift(with(replace(kBounded, "string<=6[<=3] notes", "string<=6[<=4] notes")), types),
      ElementsAre(where + "field 4 'notes' (line 4) is string<=6[<=4] in the .msg but string<=6[<=3] in "
                          "the IDL"));
  EXPECT_THAT(find_drift(with(replace(kBounded, "string<=6[<=3] notes", "string[<=3] notes")), types),
              ElementsAre(where + "field 4 'notes' (line 4) is string[<=3] in the .msg but string<=6[<=3] in "
                                  "the IDL"));
  EXPECT_THAT(
      find_drift(with(replace(kBounded, "Slot[<=4] slots", "Slot[] slots")), types),
      ElementsAre(HasSubstr("field 5 'slots' (line 5) is hubrt_test/Slot[] in the .msg but "
                            "hubrt_test/Slot[<=4] in the IDL: a sequence in the .msg, a bounded sequence "
                            "in the IDL")));
}

TEST(FindDrift, IdlTypesMustBeRosNamed) {
  const TypeInfo* types[] = {&type_info_of<plain_Point>()};
  EXPECT_THAT(find_drift({}, types),
              ElementsAre("IDL type plain::Point (in reflect_test_types.idl) is not named like a ROS 2 type "
                          "(<pkg>::msg::dds_::<Type>_), so no ROS 2 node can use it"));
}

}  // namespace
}  // namespace hubrt::msgs
