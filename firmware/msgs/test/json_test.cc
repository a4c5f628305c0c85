#include "hubrt/msgs/json.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dock_reflect.h"
#include "owned_sample.h"
#include "reflect_test_types_reflect.h"

namespace hubrt::msgs {
namespace {

using ::testing::HasSubstr;
using testing::OwnedSample;
using Json = nlohmann::ordered_json;

// A DockState built by hand, the way C code fills it (bounded strings inline, sequence buffers
// from dds_alloc).
void fill_by_hand(hub_msgs_msg_dds__DockState_& s) {
  s.header.stamp.sec = 1700000000;
  s.header.stamp.nanosec = 250000000;
  s.header.seq = 42;
  s.header.lifecycle = 3;
  std::strcpy(s.name, "dock1");
  std::strcpy(s.echo.target_type, "dock");
  std::strcpy(s.echo.target_name, "dock1");
  std::strcpy(s.echo.action, "monitor");
  s.fresh_msg = true;
  s.t_plus = 0.8f;
  s.got_reset = false;
  s.error_list._buffer = static_cast<char(*)[192]>(dds_alloc(sizeof(char[192])));
  std::strcpy(s.error_list._buffer[0], "slot sensor 2 stuck");
  s.error_list._length = s.error_list._maximum = 1;
  s.error_list._release = true;
  s.slots._buffer =
      static_cast<hub_msgs_msg_dds__DockSlot_*>(dds_alloc(2 * sizeof(hub_msgs_msg_dds__DockSlot_)));
  s.slots._buffer[0] = {"smart_tool", true};
  s.slots._buffer[1] = {"filter_tool", false};
  s.slots._length = s.slots._maximum = 2;
  s.slots._release = true;
}

const char* const kDockStateJson =
    R"({"header":{"stamp":{"sec":1700000000,"nanosec":250000000},"seq":42,"lifecycle":3},"name":"dock1",)"
    R"("echo":{"target_type":"dock","target_name":"dock1","action":"monitor"},"fresh_msg":true,"t_plus":0.8,)"
    R"("got_reset":false,"error_list":["slot sensor 2 stuck"],)"
    R"("slots":[{"name":"smart_tool","occupied":true},{"name":"filter_tool","occupied":false}]})";

TEST(ToJson, DockStateInFieldOrderWithShortestFloat) {
  OwnedSample<hub_msgs_msg_dds__DockState_> s;
  fill_by_hand(*s);
  EXPECT_EQ(to_json(s.type(), s.get()).dump(), kDockStateJson);
}

TEST(ToJson, NullStringsAndEmptySequencesOfAZeroSample) {
  OwnedSample<hub_msgs_msg_dds__DockState_> s;
  const Json j = to_json(s.type(), s.get());
  EXPECT_EQ(j["name"], "");
  EXPECT_EQ(j["error_list"], Json::array());
  EXPECT_EQ(j["slots"], Json::array());
  EXPECT_EQ(j["echo"]["action"], "");
}

TEST(ToJson, TextThatIsNotUtf8IsEscapedSoTheJsonCanAlwaysBeDumped) {
  OwnedSample<hub_msgs_msg_dds__DockState_> s;
  fill_by_hand(*s);
  std::strcpy(s->error_list._buffer[0], "unknown action 'a\xed\xa0\x80'");  // issue 11
  std::strcpy(s->slots._buffer[1].name, "\xc0\xaf\\");
  const Json j = to_json(s.type(), s.get());
  EXPECT_EQ(j["error_list"][0], "unknown action 'a\\xED\\xA0\\x80'");
  EXPECT_EQ(j["slots"][1]["name"], "\\xC0\\xAF\\\\") << "a backslash in escaped text is doubled";
  EXPECT_EQ(j["name"], "dock1") << "valid text stays as it is";
  EXPECT_NO_THROW((void)j.dump()) << "nlohmann's type_error 316 was the crash of hubctl echo --json";
  EXPECT_THAT(invalid_utf8_fields(s.type(), s.get()),
              ::testing::ElementsAre("error_list[0]", "slots[1].name"));
}

TEST(ToJson, ConvertsToPlainNlohmannJson) {
  OwnedSample<hub_msgs_msg_dds__DockState_> s;
  fill_by_hand(*s);
  const nlohmann::json plain = to_json(s.type(), s.get());
  EXPECT_EQ(plain["slots"][0]["name"], "smart_tool");
}

TEST(FromJson, FillsASampleThatCycloneCanFree) {
  OwnedSample<hub_msgs_msg_dds__DockState_> s;
  ASSERT_TRUE(from_json(s.type(), Json::parse(kDockStateJson), s.get()));
  EXPECT_STREQ(s->echo.action, "monitor");
  EXPECT_FLOAT_EQ(s->t_plus, 0.8f);
  EXPECT_EQ(s->header.seq, 42u);
  ASSERT_EQ(s->slots._length, 2u);
  EXPECT_TRUE(s->slots._release);
  EXPECT_STREQ(s->slots._buffer[1].name, "filter_tool");
  ASSERT_EQ(s->error_list._length, 1u);
  EXPECT_STREQ(s->error_list._buffer[0], "slot sensor 2 stuck");
  EXPECT_EQ(to_json(s.type(), s.get()).dump(), kDockStateJson);
}

TEST(FromJson, AbsentFieldsKeepTheirValuesAndSequencesAreReplacedWhole) {
  OwnedSample<hub_msgs_msg_dds__DockState_> s;
  fill_by_hand(*s);
  ASSERT_TRUE(
      from_json(s.type(), Json::parse(R"({"echo":{"action":"reset"},"slots":[{"name":"x"}]})"), s.get()));
  EXPECT_STREQ(s->echo.action, "reset");
  EXPECT_STREQ(s->echo.target_name, "dock1");
  EXPECT_STREQ(s->name, "dock1");
  ASSERT_EQ(s->slots._length, 1u);
  EXPECT_STREQ(s->slots._buffer[0].name, "x");
  EXPECT_FALSE(s->slots._buffer[0].occupied);
}

TEST(FromJson, ExtremeValuesOfEveryKindRoundTrip) {
  OwnedSample<hubrt_test_msg_dds__AllKinds_> s;
  const Json in = Json::parse(R"({
      "flag": true, "raw": 255, "i8": -128, "u8": 255, "i16": -32768, "u16": 65535,
      "i32": -2147483648, "u32": 4294967295, "i64": -9223372036854775808,
      "u64": 18446744073709551615, "legacy_short": 32767, "legacy_ulong": 7,
      "f32": 3.4028235e38, "f64": -1.5e-300, "text": "h\u00e9llo \"quoted\"",
      "stamp": {"sec": -1, "nanosec": 999999999},
      "inner": {"label": "in", "values": [1, 2, 3]},
      "ints": [5, -6], "words": ["a", "", "c"],
      "inners": [{"label": "i0", "values": [0, 0, 1]}, {"label": "i1", "values": [7, 8, 9]}],
      "bounded_bytes": [1, 2, 3, 4], "aliased": [-1], "matrix": [0.5, 1, 2, 3],
      "names": ["n0", "n1"], "pair": [{"label": "p0", "values": [1, 1, 1]}, {"label": "p1", "values": [2, 2, 2]}]
  })");
  ASSERT_TRUE(from_json(s.type(), in, s.get()));
  EXPECT_EQ(s->i64, std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(s->u64, std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(s->f32, std::numeric_limits<float>::max());
  EXPECT_EQ(s->raw, 255);
  EXPECT_STREQ(s->inners._buffer[1].label, "i1");
  EXPECT_EQ(s->pair[1].values[2], 2);
  EXPECT_STREQ(s->names[1], "n1");
  EXPECT_EQ(s->aliased._buffer[0], -1);
  EXPECT_EQ(to_json(s.type(), s.get()), in);
}

TEST(FromJson, NanAndInfinityBecomeNullAndNullReadsBackAsNan) {
  OwnedSample<hubrt_test_msg_dds__AllKinds_> s;
  s->f32 = std::numeric_limits<float>::infinity();
  s->f64 = std::nan("");
  const Json j = to_json(s.type(), s.get());
  EXPECT_TRUE(j["f32"].is_null());
  EXPECT_TRUE(j["f64"].is_null());
  s->f64 = 1.0;
  ASSERT_TRUE(from_json(s.type(), Json::parse(R"({"f64": null})"), s.get()));
  EXPECT_TRUE(std::isnan(s->f64));
}

struct BadJson {
  const char* name;
  const char* json;
  ErrorCode code;
  const char* message;
};

void PrintTo(const BadJson& c, std::ostream* os) {
  *os << c.json;
}

class FromJsonRejects : public ::testing::TestWithParam<BadJson> {};

TEST_P(FromJsonRejects, WithAPreciseMessageAndLeavesTheSampleUnchanged) {
  OwnedSample<hubrt_test_msg_dds__AllKinds_> s;
  ASSERT_TRUE(from_json(s.type(), Json::parse(R"({"text": "before", "ints": [1, 2], "u8": 9})"), s.get()));
  const Json before = to_json(s.type(), s.get());
  const auto result = from_json(s.type(), Json::parse(GetParam().json), s.get());
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, GetParam().code);
  EXPECT_THAT(result.error().message, HasSubstr(GetParam().message));
  EXPECT_EQ(to_json(s.type(), s.get()), before);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, FromJsonRejects,
    ::testing::Values(BadJson{"UInt8TooLarge", R"({"text": "after", "u8": 256})", ErrorCode::kOutOfRange,
                              "u8: 256 is out of range for uint8 (0..255)"},
                      BadJson{"Int8TooSmall", R"({"i8": -129})", ErrorCode::kOutOfRange,
                              "i8: -129 is out of range for int8 (-128..127)"},
                      BadJson{"NegativeUInt64", R"({"u64": -1})", ErrorCode::kOutOfRange,
                              "u64: -1 is out of range for uint64"},
                      BadJson{"Int64TooLarge", R"({"i64": 9223372036854775808})", ErrorCode::kOutOfRange,
                              "i64: 9223372036854775808 is out of range"},
                      BadJson{"Float32TooLarge", R"({"f32": 1e39})", ErrorCode::kOutOfRange,
                              "f32: 1e+39 is out of range for float32"},
                      BadJson{"FractionForInteger", R"({"i32": 1.5})", ErrorCode::kInvalidArgument,
                              "i32: expected an integer (int32:"},
                      BadJson{"StringForBool", R"({"flag": "yes"})", ErrorCode::kInvalidArgument,
                              "flag: expected true or false, got 'yes'"},
                      BadJson{"NumberForString", R"({"text": 5})", ErrorCode::kInvalidArgument,
                              "text: expected a string, got 5"},
                      BadJson{"NulInString", R"({"text": "a\u0000b"})", ErrorCode::kInvalidArgument,
                              "text: strings cannot contain a NUL"},
                      BadJson{"ArrayTooShort", R"({"matrix": [1, 2]})", ErrorCode::kInvalidArgument,
                              "matrix: expected exactly 4 elements"},
                      BadJson{"BoundedSequenceTooLong", R"({"bounded_bytes": [1, 2, 3, 4, 5]})",
                              ErrorCode::kOutOfRange, "bounded_bytes: at most 4 elements"},
                      BadJson{"NumberForSequence", R"({"ints": 3})", ErrorCode::kInvalidArgument,
                              "ints: expected an array (sequence<int32>)"},
                      BadJson{"UnknownNestedField", R"({"inners": [{"label": "ok"}, {"lable": "typo"}]})",
                              ErrorCode::kInvalidArgument,
                              "unknown field 'inners[1].lable': hubrt_test/msg/Inner has no field 'lable'; "
                              "did you mean 'label'?"},
                      BadJson{"StringInIntArray", R"({"inner": {"values": [1, 2, "3"]}})",
                              ErrorCode::kInvalidArgument, "inner.values[2]: expected an integer"},
                      BadJson{"ArrayForStruct", R"([1, 2])", ErrorCode::kInvalidArgument,
                              "expected an object (hubrt_test/msg/AllKinds), got an array of 2"}),
    [](const auto& tested) { return std::string(tested.param.name); });

TEST(FromJson, UnknownTopLevelFieldListsTheFields) {
  OwnedSample<hub_msgs_msg_dds__DockCommand_> s;
  const auto result = from_json(s.type(), Json::parse(R"({"acton": "reset"})"), s.get());
  ASSERT_FALSE(result);
  EXPECT_EQ(
      result.error().message,
      "unknown field 'acton': hub_msgs/msg/DockCommand has no field 'acton'; did you mean 'action'? (its "
      "fields: target_type, target_name, action)");
}

}  // namespace
}  // namespace hubrt::msgs
