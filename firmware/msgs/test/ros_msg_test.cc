#include "hubrt/msgs/ros_msg.h"

#include <ostream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace hubrt::msgs::ros {
namespace {

using ::testing::HasSubstr;

Expected<MsgSpec> parse(std::string_view text) {
  return parse_msg(text, "hub_msgs", "Thing", "Thing.msg");
}

TEST(ParseMsg, FieldsConstantsDefaultsAndComments) {
  const auto spec = parse(
      "# leading comment\n"
      "\n"
      "string ACTION_RESET=\"reset # not a comment\"  # comment\n"
      "byte OK = 0\n"
      "builtin_interfaces/Time stamp  # trailing\n"
      "   float32 t_plus 0.5\n"
      "string<=8 short_text\n"
      "int32[3] triple\n"
      "DockSlot[] slots\n"
      "hub_msgs/DockSlot[<=4] few\n"
      "string<=4[<=2] tags\n"
      "char c");
  ASSERT_TRUE(spec) << spec.error().message;
  ASSERT_EQ(spec->fields.size(), 8u);
  EXPECT_EQ(spec->ros_name(), "hub_msgs/msg/Thing");
  const auto& f = spec->fields;
  EXPECT_EQ(f[0].name, "stamp");
  EXPECT_EQ(f[0].element_type, "builtin_interfaces/Time");
  EXPECT_EQ(f[0].line, 5);
  EXPECT_EQ(f[1].name, "t_plus");
  EXPECT_EQ(f[1].element_type, "float32");
  EXPECT_EQ(canonical_type(f[2]), "string<=8");
  EXPECT_EQ(f[3].container, Container::kArray);
  EXPECT_EQ(canonical_type(f[3]), "int32[3]");
  EXPECT_EQ(canonical_type(f[4]), "hub_msgs/DockSlot[]") << "a bare type is in the file's package";
  EXPECT_EQ(canonical_type(f[5]), "hub_msgs/DockSlot[<=4]");
  EXPECT_EQ(canonical_type(f[6]), "string<=4[<=2]");
  EXPECT_EQ(canonical_type(f[7]), "char");
}

struct BadMsg {
  const char* name;
  const char* text;
  const char* message;
};

void PrintTo(const BadMsg& c, std::ostream* os) {
  *os << c.text;
}

class ParseMsgRejects : public ::testing::TestWithParam<BadMsg> {};

TEST_P(ParseMsgRejects, NamingFileAndLine) {
  const auto spec = parse(GetParam().text);
  ASSERT_FALSE(spec);
  EXPECT_EQ(spec.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(spec.error().message, HasSubstr(GetParam().message));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ParseMsgRejects,
    ::testing::Values(
        BadMsg{"MissingFieldName", "bool ok\nfloat32", "Thing.msg:2: expected a field name after 'float32'"},
        BadMsg{"UpperCaseFieldName", "bool Fresh",
               "Thing.msg:1: field name 'Fresh' is not a valid ROS 2 name"},
        BadMsg{"DoubleUnderscore", "bool fresh__msg", "field name 'fresh__msg' is not a valid ROS 2 name"},
        BadMsg{"DuplicateField", "bool a\nbool a", "Thing.msg:2: field 'a' already declared on line 1"},
        BadMsg{"BadArraySize", "int32[x] a", "bad array size in 'int32[x]'"},
        BadMsg{"ZeroSequenceBound", "int32[<=0] a", "bad sequence bound in 'int32[<=0]'"},
        BadMsg{"UnclosedArray", "int32[3 a", "malformed array type 'int32[3'"},
        BadMsg{"BoundOnNonString", "int32<=3 a", "only strings take a bound, not 'int32<=3'"},
        BadMsg{"MisspeltPrimitive", "flaot32 a", "'flaot32' is neither a primitive type nor a message type"},
        BadMsg{"MsgInTypeName", "hub_msgs/msg/DockSlot a", "'hub_msgs/msg/DockSlot' is neither"},
        BadMsg{"LowerCaseConstant", "int32 limit=3", "constant 'limit' must be UPPER_CASE"},
        BadMsg{"ConstantWithoutValue", "int32 LIMIT=", "constant 'LIMIT' has no value"}),
    [](const auto& tested) { return std::string(tested.param.name); });

TEST(LoadMsgPackages, MissingRootIsNotFound) {
  const auto specs = load_msg_packages("/nonexistent/ros2");
  ASSERT_FALSE(specs);
  EXPECT_EQ(specs.error().code, ErrorCode::kNotFound);
  EXPECT_THAT(specs.error().message, HasSubstr("/nonexistent/ros2"));
}

}  // namespace
}  // namespace hubrt::msgs::ros
