// The hub file's clock_tolerance_ms: how far the planner's and the hub's clocks are trusted to
// agree, or `none` for clocks that are not synced (runtime/command_age.h).
#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"

namespace hubrt::config {
namespace {

using std::chrono::milliseconds;

Expected<HubConfig> parse_with_extra(const std::string& extra) {
  auto root = YamlMap::load_string("hub: dock_ecu\n" + extra + "nodes:\n  dock: {type: dock}\n", "hub.yaml");
  if (!root) return std::move(root).error();
  return parse_hub_config(*root);
}

TEST(ClockTolerance, DefaultsToFiftyMilliseconds) {
  auto config = parse_with_extra("");
  ASSERT_TRUE(config) << config.error().message;
  ASSERT_TRUE(config->clock_tolerance.has_value());
  EXPECT_EQ(*config->clock_tolerance, milliseconds(50));
}

TEST(ClockTolerance, ReadsMillisecondsAndNone) {
  auto strict = parse_with_extra("clock_tolerance_ms: 5\n");
  ASSERT_TRUE(strict) << strict.error().message;
  EXPECT_EQ(strict->clock_tolerance, std::optional<Duration>(milliseconds(5)));
  auto zero = parse_with_extra("clock_tolerance_ms: 0\n");
  ASSERT_TRUE(zero) << zero.error().message;
  EXPECT_EQ(zero->clock_tolerance, std::optional<Duration>(milliseconds(0)));
  auto unsynced = parse_with_extra("clock_tolerance_ms: none\n");
  ASSERT_TRUE(unsynced) << unsynced.error().message;
  EXPECT_FALSE(unsynced->clock_tolerance.has_value()) << "none: the clocks are not synced";
}

TEST(ClockTolerance, RefusesNegativeOrOverTheTimeout) {
  auto negative = parse_with_extra("clock_tolerance_ms: -1\n");
  ASSERT_FALSE(negative);
  EXPECT_NE(negative.error().message.find("nor 'none'"), std::string::npos) << negative.error().message;
  auto too_long = parse_with_extra("clock_tolerance_ms: 1000\n");  // the default timeout is 1000 ms
  ASSERT_FALSE(too_long);
  EXPECT_NE(too_long.error().message.find("not below the command timeout (1000 ms)"), std::string::npos)
      << too_long.error().message;
}

}  // namespace
}  // namespace hubrt::config
