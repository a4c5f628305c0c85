// The tables the idlc plugin generated describe the C types idlc generated: names, sizes,
// descriptors, field order, kinds, offsets and nesting.
#include <cstddef>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/type_info.h"

#include "dock_reflect.h"
#include "reflect_test_types_reflect.h"

namespace hubrt::msgs {
namespace {

std::vector<std::string> field_names(const TypeInfo& t) {
  std::vector<std::string> names;
  for (const auto& f : t.fields) names.emplace_back(f.name);
  return names;
}

const FieldInfo& field(const TypeInfo& t, std::string_view name) {
  for (const auto& f : t.fields) {
    if (f.name == name) return f;
  }
  ADD_FAILURE() << t.dds_name << " has no field " << name;
  return t.fields.front();
}

TEST(GeneratedTables, DockStateNamesSizeAndDescriptor) {
  const TypeInfo& t = type_info_of<hub_msgs_msg_dds__DockState_>();
  EXPECT_EQ(t.dds_name, "hub_msgs::msg::dds_::DockState_");
  EXPECT_EQ(t.ros_name, "hub_msgs/msg/DockState");
  EXPECT_EQ(t.c_name, "hub_msgs_msg_dds__DockState_");
  EXPECT_EQ(t.idl_file, "dock.idl");
  EXPECT_EQ(t.size, sizeof(hub_msgs_msg_dds__DockState_));
  EXPECT_EQ(t.descriptor, &hub_msgs_msg_dds__DockState__desc);
  EXPECT_STREQ(t.descriptor->m_typename, "hub_msgs::msg::dds_::DockState_");
}

TEST(GeneratedTables, DockStateFieldsInWireOrderWithCOffsets) {
  const TypeInfo& t = type_info_of<hub_msgs_msg_dds__DockState_>();
  EXPECT_EQ(field_names(t), (std::vector<std::string>{"header", "name", "echo", "fresh_msg", "t_plus",
                                                      "got_reset", "error_list", "slots"}));
  EXPECT_EQ(field(t, "header").offset, offsetof(hub_msgs_msg_dds__DockState_, header));
  EXPECT_EQ(field(t, "name").offset, offsetof(hub_msgs_msg_dds__DockState_, name));
  EXPECT_EQ(field(t, "echo").offset, offsetof(hub_msgs_msg_dds__DockState_, echo));
  EXPECT_EQ(field(t, "fresh_msg").offset, offsetof(hub_msgs_msg_dds__DockState_, fresh_msg));
  EXPECT_EQ(field(t, "t_plus").offset, offsetof(hub_msgs_msg_dds__DockState_, t_plus));
  EXPECT_EQ(field(t, "got_reset").offset, offsetof(hub_msgs_msg_dds__DockState_, got_reset));
  EXPECT_EQ(field(t, "error_list").offset, offsetof(hub_msgs_msg_dds__DockState_, error_list));
  EXPECT_EQ(field(t, "slots").offset, offsetof(hub_msgs_msg_dds__DockState_, slots));
}

TEST(GeneratedTables, DockStateKindsAndNesting) {
  const TypeInfo& t = type_info_of<hub_msgs_msg_dds__DockState_>();
  EXPECT_EQ(field(t, "header").kind, FieldKind::kStruct);
  EXPECT_EQ(field(t, "header").nested, &type_info_of<hub_msgs_msg_dds__StateHeader_>());
  EXPECT_EQ(field(t, "echo").nested, &type_info_of<hub_msgs_msg_dds__DockCommand_>());
  EXPECT_EQ(field(t, "fresh_msg").kind, FieldKind::kBool);
  EXPECT_EQ(field(t, "t_plus").kind, FieldKind::kFloat32);
  EXPECT_EQ(field(t, "error_list").kind, FieldKind::kSequence);
  EXPECT_EQ(field(t, "error_list").element_kind, FieldKind::kString);
  EXPECT_EQ(field(t, "error_list").element_size, 192u) << "string<191>: char[192] inline";
  EXPECT_EQ(field(t, "error_list").string_bound, 191u);
  EXPECT_EQ(field(t, "error_list").bound, 16u);
  EXPECT_EQ(field(t, "name").string_bound, 64u);
  EXPECT_EQ(field(t, "slots").element_kind, FieldKind::kStruct);
  EXPECT_EQ(field(t, "slots").nested, &type_info_of<hub_msgs_msg_dds__DockSlot_>());
  EXPECT_EQ(field(t, "slots").element_size, sizeof(hub_msgs_msg_dds__DockSlot_));
  EXPECT_EQ(field(t, "slots").bound, 16u);

  const TypeInfo& header = type_info_of<hub_msgs_msg_dds__StateHeader_>();
  EXPECT_EQ(field_names(header), (std::vector<std::string>{"stamp", "seq", "lifecycle"}));
  EXPECT_EQ(field(header, "lifecycle").kind, FieldKind::kUInt8);
  EXPECT_EQ(field(header, "stamp").nested, &type_info_of<builtin_interfaces_msg_dds__Time_>());
  EXPECT_EQ(field(header, "seq").kind, FieldKind::kUInt64);
  EXPECT_EQ(describe_type(field(t, "slots")), "sequence<hub_msgs/msg/DockSlot, 16>");
  EXPECT_EQ(describe_type(field(t, "error_list")), "sequence<string<191>, 16>");
}

TEST(GeneratedTables, EveryKindMapsToItsCType) {
  const TypeInfo& t = type_info_of<hubrt_test_msg_dds__AllKinds_>();
  const std::vector<std::pair<std::string_view, FieldKind>> scalars = {
      {"flag", FieldKind::kBool},   {"raw", FieldKind::kOctet},          {"i8", FieldKind::kInt8},
      {"u8", FieldKind::kUInt8},    {"i16", FieldKind::kInt16},          {"u16", FieldKind::kUInt16},
      {"i32", FieldKind::kInt32},   {"u32", FieldKind::kUInt32},         {"i64", FieldKind::kInt64},
      {"u64", FieldKind::kUInt64},  {"legacy_short", FieldKind::kInt16}, {"legacy_ulong", FieldKind::kUInt32},
      {"f32", FieldKind::kFloat32}, {"f64", FieldKind::kFloat64},        {"text", FieldKind::kString},
  };
  for (const auto& [name, kind] : scalars) {
    EXPECT_EQ(field(t, name).kind, kind) << name;
    EXPECT_EQ(field(t, name).element_kind, kind) << name;
  }
  EXPECT_EQ(field(t, "i64").offset, offsetof(hubrt_test_msg_dds__AllKinds_, i64));
  EXPECT_EQ(field(t, "u8").element_size, 1u);
  EXPECT_EQ(field(t, "f64").element_size, 8u);

  EXPECT_EQ(describe_type(field(t, "ints")), "sequence<int32>");
  EXPECT_EQ(describe_type(field(t, "bounded_bytes")), "sequence<octet, 4>");
  EXPECT_EQ(describe_type(field(t, "aliased")), "sequence<int16>");  // through a typedef
  EXPECT_EQ(describe_type(field(t, "matrix")), "float64[4]");
  EXPECT_EQ(describe_type(field(t, "names")), "string[2]");
  EXPECT_EQ(field(t, "pair").kind, FieldKind::kArray);
  EXPECT_EQ(field(t, "pair").element_size, sizeof(hubrt_test_msg_dds__Inner_));
  EXPECT_EQ(field(t, "pair").nested, &type_info_of<hubrt_test_msg_dds__Inner_>());
  EXPECT_EQ(field(t, "stamp").nested, &type_info_of<builtin_interfaces_msg_dds__Time_>());
}

TEST(GeneratedTables, NestedTypeHasNoDescriptorAndPlainNamesNoRosName) {
  EXPECT_EQ(type_info_of<hubrt_test_msg_dds__Inner_>().descriptor, nullptr);
  EXPECT_NE(type_info_of<hubrt_test_msg_dds__AllKinds_>().descriptor, nullptr);
  const TypeInfo& point = type_info_of<plain_Point>();
  EXPECT_EQ(point.dds_name, "plain::Point");
  EXPECT_EQ(point.ros_name, "");
}

TEST(GeneratedTables, FileListsHoldEveryStructInDeclarationOrder) {
  const auto dock = reflected::types_of_dock();
  ASSERT_EQ(dock.size(), 3u);
  EXPECT_EQ(dock[0], &type_info_of<hub_msgs_msg_dds__DockCommand_>());
  EXPECT_EQ(dock[1], &type_info_of<hub_msgs_msg_dds__DockSlot_>());
  EXPECT_EQ(dock[2], &type_info_of<hub_msgs_msg_dds__DockState_>());
  EXPECT_EQ(reflected::types_of_reflect_test_types().size(),
            6u);  // Inner, AllKinds, Slot, Bounded, Outer, Point
}

// Whatever hubs add later: every registered table must agree with idlc's descriptor.
TEST(GeneratedTables, EveryRegisteredTableAgreesWithItsDescriptor) {
  ASSERT_FALSE(all_types().types().empty());
  for (const TypeInfo* t : all_types().types()) {
    SCOPED_TRACE(std::string(t->dds_name));
    ASSERT_NE(t->descriptor, nullptr);
    EXPECT_EQ(t->descriptor->m_typename, t->dds_name);
    EXPECT_EQ(t->descriptor->m_size, t->size);
    EXPECT_EQ(t->descriptor->m_nkeys, 0u) << "the wire contract uses keyless types";
    std::size_t previous_end = 0;
    for (const FieldInfo& f : t->fields) {
      EXPECT_GE(f.offset, previous_end) << f.name << " overlaps the field before it";
      const std::size_t size = f.kind == FieldKind::kArray      ? f.element_size * f.bound
                               : f.kind == FieldKind::kSequence ? sizeof(dds_sequence_t)
                                                                : f.element_size;
      previous_end = f.offset + size;
      EXPECT_LE(previous_end, t->size) << f.name << " ends past the struct";
      EXPECT_EQ(f.nested != nullptr, f.element_kind == FieldKind::kStruct) << f.name;
    }
  }
}

}  // namespace
}  // namespace hubrt::msgs
