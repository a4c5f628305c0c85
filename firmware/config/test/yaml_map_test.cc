#include "hubrt/config/yaml_map.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace hubrt::config {
namespace {

YamlMap load(const std::string& text) {
  auto map = YamlMap::load_string(text, "cfg.yaml");
  EXPECT_TRUE(map) << map.error().message;
  return *map;
}

TEST(YamlMap, ReadsTypedValues) {
  const YamlMap m = load("name: dock\nrate_hz: 10\nscale: 0.5\nenabled: yes\nlayout: hub\n");
  EXPECT_EQ(*m.string("name"), "dock");
  EXPECT_EQ(*m.integer("rate_hz", 1, 1000), 10);
  EXPECT_DOUBLE_EQ(*m.number("scale", 0, 1), 0.5);
  EXPECT_TRUE(*m.boolean("enabled"));
  EXPECT_EQ(*m.choice("layout", {"node_type", "hub"}), "hub");
  EXPECT_EQ(*m.integer_or("absent", 4, 0, 9), 4);
}

TEST(YamlMap, ErrorsNameFileLineKeyAndProblem) {
  const YamlMap m = load("hub:\n  rate_hz: fast\n  layout: star\n");
  const YamlMap hub = *m.map("hub");
  EXPECT_EQ(hub.integer("rate_hz", 1, 1000).error().message,
            "cfg.yaml:2:12: hub.rate_hz: expected an integer in [1, 1000], got 'fast'");
  EXPECT_EQ(hub.choice("layout", {"node_type", "hub"}).error().message,
            "cfg.yaml:3:11: hub.layout: 'star' is not one of: node_type, hub");
  EXPECT_EQ(hub.string("name").error().message, "cfg.yaml:2:3: hub: missing required key 'name'");
  EXPECT_EQ(hub.only_keys({"rate_hz"}).error().message,
            "cfg.yaml:3:3: hub.layout: unknown key (expected one of: rate_hz)");
}

TEST(YamlMap, RangeAndSyntaxErrors) {
  const YamlMap m = load("rate_hz: 5000\n");
  EXPECT_EQ(m.integer("rate_hz", 1, 1000).error().message,
            "cfg.yaml:1:10: rate_hz: 5000 is out of range [1, 1000]");
  auto broken = YamlMap::load_string("a: [1, 2\n", "bad.yaml");
  ASSERT_FALSE(broken);
  EXPECT_NE(broken.error().message.find("bad.yaml:"), std::string::npos);
  EXPECT_NE(broken.error().message.find("YAML syntax error"), std::string::npos);
  EXPECT_EQ(YamlMap::load_file("/nonexistent/x.yaml").error().code, ErrorCode::kNotFound);
}

TEST(YamlMap, ListsCarryIndexInPath) {
  const YamlMap m = load("slots:\n  - name: a\n  - name: ''\n");
  auto slots = m.list_of_maps("slots");
  ASSERT_TRUE(slots);
  ASSERT_EQ(slots->size(), 2u);
  EXPECT_EQ((*slots)[1].string("name").error().message, "cfg.yaml:3:11: slots[1].name: must not be empty");
}

// Found by fuzz/hub_yaml and fuzz/scenario: a mapping (or list) used as a key made only_keys() and
// keys() throw yaml-cpp's bad conversion out of hubd --check and hubctl play. The document is
// refused when loaded, naming where the key is.
TEST(YamlMap, KeysThatAreNotPlainNamesAreRefused) {
  for (const char* text : {"name: x\n? {a: 1}\n: y\n", "nodes:\n  - ? [1, 2]\n    : y\n"}) {
    auto map = YamlMap::load_string(text, "cfg.yaml");
    ASSERT_FALSE(map) << text;
    EXPECT_THAT(map.error().message, ::testing::HasSubstr("a key must be a plain name"));
  }
  auto nested = YamlMap::load_string("name: x\n? {a: 1}\n: y\n", "cfg.yaml");
  ASSERT_FALSE(nested);
  EXPECT_EQ(nested.error().message, "cfg.yaml:2:3: a key must be a plain name, not a mapping");
}

// Aliases repeating aliases: the readers would walk every repetition; refused instead.
TEST(YamlMap, AliasBombsAreRefused) {
  std::string text = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i < 9; ++i) {
    text += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [";
    for (int j = 0; j < 10; ++j) text += (j ? ", *a" : "*a") + std::to_string(i - 1);
    text += "]\n";
  }
  auto map = YamlMap::load_string(text, "cfg.yaml");
  ASSERT_FALSE(map);
  EXPECT_THAT(map.error().message, ::testing::HasSubstr("more than 100000 YAML nodes"));
}

}  // namespace
}  // namespace hubrt::config
