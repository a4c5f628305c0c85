#include "render.h"

#include <cmath>

#include <gtest/gtest.h>

namespace hubrt::hubctl {
namespace {

TEST(RenderHuman, NestedStateReadsLikeYaml) {
  const auto value = nlohmann::ordered_json::parse(R"({
    "header": {"stamp": {"sec": 5, "nanosec": 10}, "seq": 42, "lifecycle": 3},
    "name": "dock",
    "echo": {"target_type": "dock", "target_name": "", "action": "monitor"},
    "fresh_msg": true,
    "t_plus": 1.5,
    "error_list": [],
    "slots": [{"name": "smart_tool", "occupied": false}, {"name": "spare", "occupied": true}]
  })");
  EXPECT_EQ(render_human(value),
            "header:\n"
            "  stamp:\n"
            "    sec: 5\n"
            "    nanosec: 10\n"
            "  seq: 42\n"
            "  lifecycle: 3 (operational)\n"
            "name: dock\n"
            "echo:\n"
            "  target_type: dock\n"
            "  target_name: ''\n"
            "  action: monitor\n"
            "fresh_msg: true\n"
            "t_plus: 1.5\n"
            "error_list: []\n"
            "slots:\n"
            "  - name: smart_tool\n"
            "    occupied: false\n"
            "  - name: spare\n"
            "    occupied: true\n");
}

TEST(RenderHuman, LifecycleNamedOnlyInAHeader) {
  const auto value = nlohmann::ordered_json::parse(
      R"({"header": {"lifecycle": 4}, "tool": {"header": {"lifecycle": 200}}, "lifecycle": 2})");
  EXPECT_EQ(render_human(value),
            "header:\n"
            "  lifecycle: 4 (fault)\n"
            "tool:\n"
            "  header:\n"
            "    lifecycle: 200 (unknown)\n"
            "lifecycle: 2\n");
}

TEST(RenderHuman, ScalarListsStayOnOneLine) {
  const auto value = nlohmann::ordered_json::parse(R"({"error_list": ["a", "b c"]})");
  EXPECT_EQ(render_human(value), "error_list: [a, b c]\n");
}

// A float not measured is NaN on the wire and null in JSON (no NaN there); the human form says NaN.
TEST(RenderHuman, ANullFloatReadsNaN) {
  const auto value =
      nlohmann::ordered_json::parse(R"({"drive_online": false, "position_mm": null, "target_mm": 250.5})");
  EXPECT_EQ(render_human(value), "drive_online: false\nposition_mm: NaN\ntarget_mm: 250.5\n");
  EXPECT_TRUE(std::isnan(number_or_nan(value, "position_mm")));
  EXPECT_TRUE(std::isnan(number_or_nan(value, "missing")));
  EXPECT_TRUE(std::isnan(number_or_nan(value, "drive_online")));
  EXPECT_EQ(number_or_nan(value, "target_mm"), 250.5);
  EXPECT_TRUE(std::isnan(number_or_nan(nlohmann::ordered_json(3), "x")));
}

}  // namespace
}  // namespace hubrt::hubctl
