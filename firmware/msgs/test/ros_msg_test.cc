#include "hubrt/msgs/ros_msg.h"

#include <ostream>
#include <string>
#include <vector>

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
  EXPECT_EQ(f[1].default_value, "0.5");
  EXPECT_EQ(f[0].default_value, "");
  ASSERT_EQ(spec->constants.size(), 2u);
  EXPECT_EQ(spec->constants[0].type, "string");
  EXPECT_EQ(spec->constants[0].name, "ACTION_RESET");
  EXPECT_EQ(spec->constants[0].value, "reset # not a comment");
  EXPECT_EQ(spec->constants[1].value, "0");
  EXPECT_EQ(spec->constants[1].line, 4);
}

// Constant values as rosidl_adapter reads them (parser.py, parse_primitive_value_string), kept
// normalised for the IDL.
TEST(ParseMsg, ConstantValuesAreCheckedAndNormalisedAsRosidlDoes) {
  const auto spec = parse(
      "bool A=TRUE\nbool B=0\nbyte C=0x1F\nint8 D=-128\nuint64 E=18446744073709551615\nint64 F=-0b101\n"
      "float32 G=1\nfloat64 H=-2.5e-3\nstring I='single \\' quoted'\nstring J=\"a 'b'\"\nstring K=bare "
      "words\n"
      "int32 L=+7\n");
  ASSERT_TRUE(spec) << spec.error().message;
  std::vector<std::string> values;
  for (const auto& c : spec->constants) values.push_back(c.value);
  EXPECT_THAT(values,
              ::testing::ElementsAre("true", "false", "31", "-128", "18446744073709551615", "-5", "1.0",
                                     "-0.0025", "single ' quoted", "a 'b'", "bare words", "7"));
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
        BadMsg{"ConstantWithoutValue", "int32 LIMIT=", "constant 'LIMIT' has no value"},
        BadMsg{"ConstantOutOfRange", "uint8 LIMIT=256",
               "Thing.msg:1: constant 'LIMIT' = 256: must be a valid integer value >= 0 and <= 255"},
        BadMsg{"NegativeBelowRange", "int16 LOW=-32769",
               "must be a valid integer value >= -32768 and <= 32767"},
        BadMsg{"Int64Overflow", "int64 BIG=9223372036854775808", "must be a valid integer value"},
        BadMsg{"NotANumber", "int32 LIMIT=3.5", "constant 'LIMIT' = 3.5: must be a valid integer value"},
        BadMsg{"BoolWord", "bool ON=yes", "must be either 'true' / '1' or 'false' / '0'"},
        BadMsg{"FloatNotFinite", "float64 X=inf", "must be a finite floating point number"},
        BadMsg{"Float32Range", "float32 X=1e39", "must be within float32's range"},
        BadMsg{"UnescapedInnerQuote", "string S=\"a\"b\"", "string inner quotes not properly escaped"},
        BadMsg{"ArrayConstant", "int32[2] PAIR=[1, 2]", "its type 'int32[2]' must be a primitive type"},
        BadMsg{"BoundedStringConstant", "string<=4 S=abc", "its type 'string<=4' must be a primitive type"},
        BadMsg{"MessageConstant", "DockSlot S=1", "its type 'DockSlot' must be a primitive type"},
        BadMsg{"DuplicateConstant", "int32 A=1\nint32 A=2",
               "Thing.msg:2: constant 'A' already declared on line 1"}),
    [](const auto& tested) { return std::string(tested.param.name); });

TEST(LoadMsgPackages, MissingRootIsNotFound) {
  const auto specs = load_msg_packages("/nonexistent/ros2");
  ASSERT_FALSE(specs);
  EXPECT_EQ(specs.error().code, ErrorCode::kNotFound);
  EXPECT_THAT(specs.error().message, HasSubstr("/nonexistent/ros2"));
}

}  // namespace
}  // namespace hubrt::msgs::ros
