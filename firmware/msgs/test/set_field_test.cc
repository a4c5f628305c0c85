#include "hubrt/msgs/set_field.h"

#include <cstdint>
#include <limits>
#include <ostream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hubrt/msgs/json.h"

#include "diagnostic_msgs_reflect.h"
#include "dock_reflect.h"
#include "owned_sample.h"
#include "reflect_test_types_reflect.h"

namespace hubrt::msgs {
namespace {

using ::testing::HasSubstr;
using testing::OwnedSample;

TEST(SetField, DottedPathIntoANestedStruct) {
  OwnedSample<hub_msgs_msg_dds__DockState_> s;
  ASSERT_TRUE(set_field(s.type(), s.get(), "echo.action", "reset"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "echo.action", "monitor"));  // replaces, frees the old
  ASSERT_TRUE(set_field(s.type(), s.get(), "header.stamp.sec", "-5"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "header.seq", "18446744073709551615"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "t_plus", "1.25"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "fresh_msg", "true"));
  EXPECT_STREQ(s->echo.action, "monitor");
  EXPECT_EQ(s->header.stamp.sec, -5);
  EXPECT_EQ(s->header.seq, std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(s->t_plus, 1.25f);
  EXPECT_TRUE(s->fresh_msg);
  EXPECT_STREQ(s->echo.target_name, "") << "untouched fields stay as they were";
}

TEST(SetField, IndexAtTheLengthAppendsOtherIndicesReplace) {
  OwnedSample<hub_msgs_msg_dds__DockState_> s;
  ASSERT_TRUE(set_field(s.type(), s.get(), "error_list[0]", "first"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "error_list[1]", "second"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "error_list[0]", "FIRST"));
  ASSERT_EQ(s->error_list._length, 2u);
  EXPECT_STREQ(s->error_list._buffer[0], "FIRST");
  EXPECT_STREQ(s->error_list._buffer[1], "second");

  ASSERT_TRUE(set_field(s.type(), s.get(), "slots[0].occupied", "1"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "slots[0].name", "smart_tool"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "slots[1].name", "filter_tool"));
  ASSERT_EQ(s->slots._length, 2u);
  EXPECT_TRUE(s->slots._buffer[0].occupied);
  EXPECT_STREQ(s->slots._buffer[0].name, "smart_tool");
  EXPECT_STREQ(s->slots._buffer[1].name, "filter_tool");
  EXPECT_FALSE(s->slots._buffer[1].occupied) << "an appended element starts zeroed";
}

TEST(SetField, WholeStructsAndSequencesTakeJson) {
  OwnedSample<hub_msgs_msg_dds__DockState_> s;
  ASSERT_TRUE(set_field(s.type(), s.get(), "slots[0].name", "old"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "slots", R"([{"name":"a","occupied":true},{"name":"b"}])"));
  ASSERT_EQ(s->slots._length, 2u);
  EXPECT_STREQ(s->slots._buffer[1].name, "b");
  ASSERT_TRUE(set_field(s.type(), s.get(), "echo", R"({"target_type":"dock","action":"reset"})"));
  EXPECT_STREQ(s->echo.target_type, "dock");
  EXPECT_STREQ(s->echo.action, "reset");
  ASSERT_TRUE(set_field(s.type(), s.get(), "slots[1]", R"({"occupied":true})"));
  EXPECT_TRUE(s->slots._buffer[1].occupied);
  EXPECT_STREQ(s->slots._buffer[1].name, "b");
}

// Two appends on one path: a new status, and a new key/value inside it (diagnostic_msgs layout).
TEST(SetField, AppendsThroughNestedSequences) {
  OwnedSample<diagnostic_msgs_msg_dds__DiagnosticArray_> s;
  ASSERT_TRUE(set_field(s.type(), s.get(), "status[0].values[0].key", "temperature"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "status[0].values[0].value", "41.5"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "status[0].level", "2"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "header.frame_id", "dock1"));
  ASSERT_EQ(s->status._length, 1u);
  ASSERT_EQ(s->status._buffer[0].values._length, 1u);
  EXPECT_STREQ(s->status._buffer[0].values._buffer[0].key, "temperature");
  EXPECT_STREQ(s->status._buffer[0].values._buffer[0].value, "41.5");
  EXPECT_EQ(s->status._buffer[0].level, 2);
  const auto past = set_field(s.type(), s.get(), "status[1].values[1].key", "x");
  ASSERT_FALSE(past);
  EXPECT_THAT(past.error().message,
              HasSubstr("status[1].values[1]: index 1 is past the end of 'values' (length 0"));
  EXPECT_EQ(s->status._length, 1u) << "nothing appended by a failed path";
}

TEST(SetField, EveryScalarKindFromText) {
  OwnedSample<hubrt_test_msg_dds__AllKinds_> s;
  ASSERT_TRUE(set_field(s.type(), s.get(), "raw", "0xff"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "i8", "-128"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "u16", "65535"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "i64", "-9223372036854775808"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "f64", "-2.5e-3"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "f32", "inf"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "matrix[3]", "7.5"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "names[1]", "second"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "pair[1].values[2]", "12"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "inners[0].values[1]", "3"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "text", "with = and spaces"));
  EXPECT_EQ(s->raw, 255);
  EXPECT_EQ(s->i8, -128);
  EXPECT_EQ(s->u16, 65535);
  EXPECT_EQ(s->i64, std::numeric_limits<std::int64_t>::min());
  EXPECT_DOUBLE_EQ(s->f64, -2.5e-3);
  EXPECT_EQ(s->f32, std::numeric_limits<float>::infinity());
  EXPECT_EQ(s->matrix[3], 7.5);
  EXPECT_STREQ(s->names[1], "second");
  EXPECT_EQ(s->pair[1].values[2], 12);
  ASSERT_EQ(s->inners._length, 1u);
  EXPECT_EQ(s->inners._buffer[0].values[1], 3);
  EXPECT_STREQ(s->text, "with = and spaces");
}

struct BadSet {
  const char* name;
  const char* path;
  const char* text;
  ErrorCode code;
  const char* message;
};

void PrintTo(const BadSet& c, std::ostream* os) {
  *os << c.path << "=" << c.text;
}

class SetFieldRejects : public ::testing::TestWithParam<BadSet> {};

TEST_P(SetFieldRejects, WithAPreciseMessageAndLeavesTheSampleUnchanged) {
  OwnedSample<hubrt_test_msg_dds__AllKinds_> s;
  ASSERT_TRUE(set_field(s.type(), s.get(), "ints", "[1, 2]"));
  ASSERT_TRUE(set_field(s.type(), s.get(), "text", "before"));
  const auto before = to_json(s.type(), s.get());
  const auto result = set_field(s.type(), s.get(), GetParam().path, GetParam().text);
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, GetParam().code);
  EXPECT_THAT(result.error().message, HasSubstr(GetParam().message));
  EXPECT_EQ(to_json(s.type(), s.get()), before);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SetFieldRejects,
    ::testing::Values(
        BadSet{"UInt8TooLarge", "u8", "256", ErrorCode::kOutOfRange,
               "u8: 256 is out of range for uint8 (0..255)"},
        BadSet{"Int8TooSmall", "i8", "-129", ErrorCode::kOutOfRange,
               "i8: -129 is out of range for int8 (-128..127)"},
        BadSet{"NegativeUInt32", "u32", "-1", ErrorCode::kOutOfRange,
               "u32: -1 is out of range for uint32 (0..4294967295)"},
        BadSet{"UInt64TooLarge", "u64", "18446744073709551616", ErrorCode::kOutOfRange,
               "is out of range for uint64"},
        BadSet{"Int64TooSmall", "i64", "-9223372036854775809", ErrorCode::kOutOfRange,
               "is out of range for int64"},
        BadSet{"Float32TooLarge", "f32", "1e39", ErrorCode::kOutOfRange,
               "f32: 1e+39 is out of range for float32"},
        BadSet{"Float64Overflow", "f64", "1e999", ErrorCode::kOutOfRange,
               "f64: 1e999 is out of range for float64"},
        BadSet{"WordForFloat", "f64", "fast", ErrorCode::kInvalidArgument,
               "f64: expected a number (float64), got 'fast'"},
        BadSet{"TrailingGarbage", "i32", "12abc", ErrorCode::kInvalidArgument,
               "i32: expected an integer (int32: -2147483648..2147483647)"},
        BadSet{"EmptyInteger", "i32", "", ErrorCode::kInvalidArgument, "i32: expected an integer"},
        BadSet{"WordForBool", "flag", "yes", ErrorCode::kInvalidArgument,
               "flag: expected true or false, got 'yes'"},
        BadSet{"IndexPastTheEnd", "ints[3]", "1", ErrorCode::kOutOfRange,
               "ints[3]: index 3 is past the end of 'ints' (length 2; index 2 appends)"},
        BadSet{"ArrayIndexOutOfRange", "matrix[4]", "1", ErrorCode::kOutOfRange,
               "matrix[4]: index 4 is out of range for float64[4] (0..3)"},
        BadSet{"IndexOnString", "text[0]", "x", ErrorCode::kInvalidArgument,
               "'text' is a string, not a sequence or array; it takes no index"},
        BadSet{"FieldOfString", "text.size", "x", ErrorCode::kInvalidArgument,
               "text is a string, so it has no field 'size'"},
        BadSet{"UnknownNestedField", "inner.lable", "x", ErrorCode::kInvalidArgument,
               "unknown field 'inner.lable': hubrt_test/msg/Inner has no field 'lable'; did you mean "
               "'label'? (its "
               "fields: label, values)"},
        BadSet{"WordInNestedArray", "inners[0].values[1]", "oops", ErrorCode::kInvalidArgument,
               "inners[0].values[1]: expected an integer"},
        BadSet{"AppendPastTheEnd", "inners[1].label", "x", ErrorCode::kOutOfRange,
               "index 1 is past the end of 'inners' (length 0; index 0 appends)"},
        BadSet{"MalformedJson", "ints", "[1, 2", ErrorCode::kInvalidArgument,
               "ints: expected a JSON value for sequence<int32>, got '[1, 2'"},
        BadSet{"JsonArrayTooShort", "inner", R"({"values": [1]})", ErrorCode::kInvalidArgument,
               "inner.values: expected exactly 3 elements"},
        BadSet{"EmptyPathSegment", "inner..label", "x", ErrorCode::kInvalidArgument,
               "malformed field path 'inner..label': expected a field name at position 7"},
        BadSet{"NonNumericIndex", "ints[x]", "1", ErrorCode::kInvalidArgument,
               "malformed field path 'ints[x]': expected an index at position 6"},
        BadSet{"UnclosedIndex", "ints[0", "1", ErrorCode::kInvalidArgument, "expected ']' at position 7"},
        BadSet{"EmptyPath", "", "1", ErrorCode::kInvalidArgument,
               "malformed field path '': expected a field name at position 1"}),
    [](const auto& tested) { return std::string(tested.param.name); });

TEST(SetField, UnknownTopLevelFieldSuggestsAndLists) {
  OwnedSample<hub_msgs_msg_dds__DockState_> s;
  const auto result = set_field(s.type(), s.get(), "echo.acton", "reset");
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().message,
            "unknown field 'echo.acton': hub_msgs/msg/DockCommand has no field 'acton'; did you mean "
            "'action'? (its "
            "fields: target_type, target_name, action)");
  const auto far = set_field(s.type(), s.get(), "zzz", "1");
  ASSERT_FALSE(far);
  EXPECT_THAT(far.error().message, ::testing::Not(HasSubstr("did you mean")));
  EXPECT_THAT(far.error().message, HasSubstr("its fields: header, name, echo, fresh_msg"));
}

TEST(SetField, BoundedSequenceStopsAtItsBound) {
  OwnedSample<hubrt_test_msg_dds__AllKinds_> s;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(set_field(s.type(), s.get(), "bounded_bytes[" + std::to_string(i) + "]", "1"));
  }
  const auto result = set_field(s.type(), s.get(), "bounded_bytes[4]", "1");
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::kOutOfRange);
  EXPECT_THAT(result.error().message, HasSubstr("'bounded_bytes' holds at most 4 elements"));
  EXPECT_EQ(s->bounded_bytes._length, 4u);
}

TEST(SetField, AFailedValueDoesNotAppend) {
  OwnedSample<hub_msgs_msg_dds__DockState_> s;
  ASSERT_FALSE(set_field(s.type(), s.get(), "slots[0].occupied", "maybe"));
  EXPECT_EQ(s->slots._length, 0u);
  EXPECT_EQ(s->slots._buffer, nullptr);
}

}  // namespace
}  // namespace hubrt::msgs

namespace hubrt::msgs {
namespace {

// Bounded strings (char[N+1] inline) and bounded sequences of them: written in place, refused
// over the bound with the bound named, read back by to_json.
TEST(SetField, BoundedStringsAreWrittenInPlaceAndRefusedOverTheirBound) {
  OwnedSample<hubrt_test_msg_dds__Bounded_> s;
  ASSERT_TRUE(set_field(s.type(), s.get(), "label", "lock"));
  EXPECT_STREQ(s->label, "lock");
  const auto too_long = set_field(s.type(), s.get(), "label", "123456789");
  ASSERT_FALSE(too_long);
  EXPECT_THAT(too_long.error().message, HasSubstr("label: at most 8 bytes (string<8>), got 9"));
  EXPECT_STREQ(s->label, "lock") << "a refused value changes nothing";

  ASSERT_TRUE(set_field(s.type(), s.get(), "notes", R"(["a", "bb"])"));
  ASSERT_EQ(s->notes._length, 2u);
  EXPECT_STREQ(s->notes._buffer[1], "bb");
  const auto long_note = set_field(s.type(), s.get(), "notes", R"(["1234567"])");
  ASSERT_FALSE(long_note);
  EXPECT_THAT(long_note.error().message, HasSubstr("notes[0]: at most 6 bytes"));
  EXPECT_FALSE(set_field(s.type(), s.get(), "notes", R"(["a", "b", "c", "d"])")) << "sequence bound 3";
  ASSERT_TRUE(set_field(s.type(), s.get(), "slots[0].name", "slot"));
  EXPECT_EQ(to_json(s.type(), s.get())["notes"], nlohmann::ordered_json::parse(R"(["a", "bb"])"));
  EXPECT_EQ(to_json(s.type(), s.get())["slots"][0]["name"], "slot");
}

}  // namespace
}  // namespace hubrt::msgs
