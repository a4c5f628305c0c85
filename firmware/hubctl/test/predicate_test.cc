// Scenario conditions on States: how they are written, what they say about a State, and what
// they refuse.
#include "predicate.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace hubrt::hubctl {
namespace {

using ::testing::HasSubstr;

const nlohmann::ordered_json kState = nlohmann::ordered_json::parse(R"({
  "name": "lift", "fresh_msg": true, "t_plus": 1.5, "at": "float", "position_mm": 250.00001,
  "error_list": ["command timeout: no valid command for 1.20 s", "drive not answering"],
  "empty_list": [], "note": "",
  "slots": [{"name": "ladder_frame_tool", "occupied": true}, {"name": "smart_tool", "occupied": false}],
  "last_result": {"run_id": 12, "ok": true, "torque_nm": 10.0},
  "lift_mm": null
})");

PredicateVerdict eval(std::string_view text) {
  auto predicate = parse_predicate(text);
  EXPECT_TRUE(predicate) << predicate.error().message;
  if (!predicate) return {};
  return evaluate(*predicate, kState);
}

bool holds(std::string_view text) {
  const PredicateVerdict v = eval(text);
  EXPECT_FALSE(v.broken) << text << ": " << v.detail;
  return v.holds;
}

TEST(Predicate, ComparesStringsNumbersAndBooleans) {
  EXPECT_TRUE(holds("at == float"));
  EXPECT_TRUE(holds("at == 'float'"));
  EXPECT_TRUE(holds("at == \"float\""));
  EXPECT_FALSE(holds("at == home"));
  EXPECT_TRUE(holds("at != home"));
  EXPECT_TRUE(holds("fresh_msg == true"));
  EXPECT_FALSE(holds("fresh_msg == false"));
  EXPECT_TRUE(holds("fresh_msg != false"));
  EXPECT_TRUE(holds("position_mm == 250")) << "float32 values compare with a relative tolerance";
  EXPECT_TRUE(holds("position_mm >= 250"));
  EXPECT_TRUE(holds("position_mm <= 250"));
  EXPECT_FALSE(holds("position_mm < 250"));
  EXPECT_FALSE(holds("position_mm > 250"));
  EXPECT_TRUE(holds("position_mm > 249.5"));
  EXPECT_TRUE(holds("t_plus < 2"));
  EXPECT_TRUE(holds("lift_mm == nan")) << "a NaN float arrives as null";
}

TEST(Predicate, ReachesIntoStructsAndListsByIndexOrName) {
  EXPECT_TRUE(holds("last_result.run_id == 12"));
  EXPECT_TRUE(holds("last_result.ok == true"));
  EXPECT_TRUE(holds("slots[0].occupied == true"));
  EXPECT_TRUE(holds("slots[smart_tool].occupied == false"));
  EXPECT_TRUE(holds("slots[ladder_frame_tool].name == ladder_frame_tool"));
}

TEST(Predicate, ListsContainSubstringsOrAreEmpty) {
  EXPECT_TRUE(holds("error_list contains command timeout"));
  EXPECT_TRUE(holds("error_list contains 'not answering'"));
  EXPECT_FALSE(holds("error_list contains pressure"));
  EXPECT_TRUE(holds("error_list lacks pressure"));
  EXPECT_FALSE(holds("error_list lacks drive"));
  EXPECT_TRUE(holds("error_list not_empty"));
  EXPECT_FALSE(holds("error_list empty"));
  EXPECT_TRUE(holds("empty_list empty"));
  EXPECT_TRUE(holds("note empty"));
  EXPECT_TRUE(holds("at contains flo"));
}

TEST(Predicate, TheVerdictShowsTheValue) {
  const PredicateVerdict v = eval("at == home");
  EXPECT_FALSE(v.holds);
  EXPECT_EQ(v.detail, "at is \"float\"");
}

TEST(Predicate, AFieldThatIsNotThereCannotBeWaitedFor) {
  const PredicateVerdict missing = eval("positon_mm > 3");
  EXPECT_TRUE(missing.broken);
  EXPECT_THAT(missing.detail, HasSubstr("no field 'positon_mm' (fields: name, fresh_msg"));
  const PredicateVerdict nested = eval("last_result.angle > 3");
  EXPECT_TRUE(nested.broken);
  EXPECT_THAT(nested.detail, HasSubstr("no field 'angle' in 'last_result'"));
  const PredicateVerdict no_slot = eval("slots[filter_tool].occupied == true");
  EXPECT_TRUE(no_slot.broken);
  EXPECT_THAT(no_slot.detail,
              HasSubstr("no element named 'filter_tool' (names: ladder_frame_tool, smart_tool)"));
  EXPECT_TRUE(eval("slots[5].occupied == true").broken);
  EXPECT_TRUE(eval("at[0] == x").broken);
}

TEST(Predicate, AComparisonThatDoesNotFitTheFieldIsRefused) {
  EXPECT_TRUE(eval("fresh_msg > true").broken);
  EXPECT_TRUE(eval("fresh_msg == maybe").broken);
  EXPECT_TRUE(eval("position_mm == high").broken);
  EXPECT_TRUE(eval("at < home").broken);
  EXPECT_TRUE(eval("last_result == 3").broken);
  EXPECT_TRUE(eval("fresh_msg empty").broken);
}

TEST(Predicate, MalformedConditionsAreRefusedWithTheReason) {
  const struct {
    const char* text;
    const char* expected;
  } cases[] = {
      {"", "empty condition"},
      {"at", "no operator"},
      {"at = home", "unknown operator '='"},
      {"at ==", "'==' needs a value"},
      {"error_list empty now", "'empty' takes no value"},
      {"slots[.occupied == true", "bad [...]"},
      {"slots..x == 1", "expected a field name"},
      {"a-b == 1", "expected '.' or '['"},
  };
  for (const auto& c : cases) {
    auto parsed = parse_predicate(c.text);
    ASSERT_FALSE(parsed) << c.text;
    EXPECT_THAT(parsed.error().message, HasSubstr(c.expected)) << c.text;
  }
}

}  // namespace
}  // namespace hubrt::hubctl
