// The IDL hubrt_msg2idl writes from .msg files: the fixture of every shape against the IDL written
// by hand from rosidl's mapping (hubrt/msgs/msg_to_idl.h cites it), and what the C types cannot
// carry refused with the file and line.
#include "hubrt/msgs/msg_to_idl.h"

#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace hubrt::msgs {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::string read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.is_open()) << path;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

ros::MsgSpec fixture(const std::string& name) {
  const std::string path = std::string(HUBRT_MSG_FIXTURE_DIR) + "/" + name + ".msg";
  auto spec = ros::parse_msg(read(path), "msg_fixture", name, path);
  EXPECT_TRUE(spec) << spec.error().message;
  return spec ? *spec : ros::MsgSpec{};
}

ros::MsgSpec msg(const std::string& name, const std::string& text) {
  auto spec = ros::parse_msg(text, "hub_msgs", name, name + ".msg");
  EXPECT_TRUE(spec) << spec.error().message;
  return spec ? *spec : ros::MsgSpec{};
}

TEST(MsgToIdl, TheFixtureOfEveryShapeMapsAsRosidlMapsIt) {
  const IdlFileSpec file{"shapes",
                         {fixture("Shapes"), fixture("Part"), fixture("Empty")},
                         {{"builtin_interfaces/Time", "builtin_interfaces"}}};
  const Expected<std::string> idl = idl_from_msgs(file);
  ASSERT_TRUE(idl) << idl.error().message;
  EXPECT_EQ(*idl, read(std::string(HUBRT_MSG_FIXTURE_DIR) + "/shapes.idl.expected"));
}

TEST(MsgToIdl, TypesOfOtherFilesAreIncludedOnceInSortedOrderAndTheFileItselfNever) {
  const IdlFileSpec file{"dock",
                         {msg("DockSlot", "string<=64 name\nstring<=4[2] tags\n"),
                          msg("DockState",
                              "StateHeader header\nDockSlot[<=16] slots\n"
                              "builtin_interfaces/Time stamp\nStateHeader again\n")},
                         {{"hub_msgs/StateHeader", "hub_msgs_common"},
                          {"builtin_interfaces/Time", "builtin_interfaces"},
                          {"hub_msgs/DockSlot", "dock"}}};
  const Expected<std::string> idl = idl_from_msgs(file);
  ASSERT_TRUE(idl) << idl.error().message;
  EXPECT_THAT(*idl, HasSubstr("#include \"builtin_interfaces.idl\"\n#include \"hub_msgs_common.idl\"\n\n"));
  EXPECT_THAT(*idl, Not(HasSubstr("#include \"dock.idl\"")));
  EXPECT_THAT(*idl, HasSubstr("sequence<hub_msgs::msg::dds_::DockSlot_, 16> slots;"));
  // (The reflection plugin refuses arrays of bounded strings, so the fixture cannot hold one.)
  EXPECT_THAT(*idl, HasSubstr("string<4> tags[2];"));
  // DockSlot comes before the DockState that uses it, whatever the order given.
  EXPECT_LT(idl->find("struct DockSlot_"), idl->find("struct DockState_"));
}

struct Refused {
  const char* name;
  const char* text;
  const char* message;
};

void PrintTo(const Refused& c, std::ostream* os) {
  *os << c.text;
}

class MsgToIdlRefuses : public ::testing::TestWithParam<Refused> {};

TEST_P(MsgToIdlRefuses, NamingFileAndLine) {
  const IdlFileSpec file{"thing", {msg("Thing", GetParam().text)}, {}};
  const Expected<std::string> idl = idl_from_msgs(file);
  ASSERT_FALSE(idl);
  EXPECT_EQ(idl.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(idl.error().message, HasSubstr(GetParam().message));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MsgToIdlRefuses,
    ::testing::Values(
        Refused{"UnknownNestedType", "bool ok\nDockSlot slot\n",
                "Thing.msg:2: field 'slot': no .msg of this message target or of its DEPENDS defines "
                "'hub_msgs/DockSlot'"},
        Refused{"DefaultValue", "int32 count 5\n",
                "Thing.msg:1: field 'count' has a default value (5): not supported"},
        Refused{"WideString", "wstring text\n", "Thing.msg:1: field 'text': wstring is not supported"},
        Refused{"QuoteInAStringConstant", "string SAY='a \"b\"'\nbool ok\n",
                "Thing.msg:1: constant 'SAY': a string constant may hold only printable ASCII"},
        Refused{"BackslashInAStringConstant", "string PATH=a\\b\nbool ok\n", "constant 'PATH'"},
        Refused{"ContainsItself", "Thing inner\n", "hub_msgs/Thing contains itself"}),
    [](const auto& tested) { return std::string(tested.param.name); });

}  // namespace
}  // namespace hubrt::msgs
