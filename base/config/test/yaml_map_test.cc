#include "hubrt/config/yaml_map.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hubrt/config/config_file.h"

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

// yaml-cpp keeps both entries of a repeated key and node["rate_hz"] finds the first: the
// document is refused instead, at the second one, wherever it is.
TEST(YamlMap, ARepeatedTopLevelKeyIsRefusedAtItsSecondLine) {
  auto loaded = YamlMap::load_string("rate_hz: 10\nname: x\nrate_hz: 500\n", "cfg.yaml");
  ASSERT_FALSE(loaded) << "the second rate_hz was silently ignored";
  EXPECT_EQ(loaded.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(loaded.error().message, "cfg.yaml:3:1: rate_hz: declared twice (first at line 1)");
}

TEST(YamlMap, ARepeatedNestedKeyIsRefusedWithItsPath) {
  auto nested = YamlMap::load_string("a:\n  b:\n    c: 1\n    d: 2\n    c: 3\n", "cfg.yaml");
  ASSERT_FALSE(nested);
  EXPECT_EQ(nested.error().message, "cfg.yaml:5:5: a.b.c: declared twice (first at line 3)");
  auto in_list = YamlMap::load_string("slots:\n  - {name: a, name: b}\n", "cfg.yaml");
  ASSERT_FALSE(in_list);
  EXPECT_EQ(in_list.error().message, "cfg.yaml:2:15: slots[0].name: declared twice (first at line 2)");
  // The same key in two different mappings is no repetition.
  EXPECT_TRUE(YamlMap::load_string("a: {x: 1}\nb: {x: 2}\n", "cfg.yaml"));
}

TEST(YamlMap, InvalidUtf8IsRefusedWhereItIs) {
  // "Grün" in Latin-1 (FC) instead of UTF-8 (C3 BC), in a value on line 2.
  auto latin1 = YamlMap::load_string("name: dock\ndescription: Gr\xFCn\n", "cfg.yaml");
  ASSERT_FALSE(latin1) << "invalid UTF-8 was accepted";
  EXPECT_EQ(latin1.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(latin1.error().message,
            "cfg.yaml:2:16: not valid UTF-8 (byte 0xFC): configuration files are UTF-8 text (RFC 3629)");
  // A surrogate (ED A0 80) in a key, after a valid two-byte character: the column counts
  // characters.
  auto surrogate = YamlMap::load_string("\xC3\xB6\xED\xA0\x80: 1\n", "cfg.yaml");
  ASSERT_FALSE(surrogate);
  EXPECT_TRUE(surrogate.error().message.starts_with("cfg.yaml:1:2: not valid UTF-8 (byte 0xED): "))
      << surrogate.error().message;
  // Valid multi-byte text is fine.
  auto valid = YamlMap::load_string("description: Gr\xC3\xBCn \xF0\x9F\xA4\x96\n", "cfg.yaml");
  ASSERT_TRUE(valid) << valid.error().message;
  EXPECT_EQ(*valid->string("description"), "Gr\xC3\xBCn \xF0\x9F\xA4\x96");
}

// A folder of its own for files the tests make; removed at the end.
class YamlMapFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / fmt::format("hubrt-yaml-map-{}", getpid());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(YamlMapFiles, ADirectoryIsSaidToBeOne) {
  const auto folder = dir_ / "dock.yaml";
  std::filesystem::create_directory(folder);
  auto loaded = YamlMap::load_file(folder.string());
  ASSERT_FALSE(loaded);
  EXPECT_EQ(loaded.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(loaded.error().message, folder.string() + ": is a directory, not a file");
}

TEST_F(YamlMapFiles, ASymbolicLinkLoopIsSaidToBeOne) {
  const auto a = dir_ / "a.yaml";
  const auto b = dir_ / "b.yaml";
  std::filesystem::create_symlink(b, a);
  std::filesystem::create_symlink(a, b);
  auto loaded = YamlMap::load_file(a.string());
  ASSERT_FALSE(loaded);
  EXPECT_EQ(loaded.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(loaded.error().message,
            a.string() + ": is a symbolic link loop (too many levels of symbolic links)");
}

TEST_F(YamlMapFiles, MissingFilesAndDanglingLinksDoNotExist) {
  const auto missing = dir_ / "missing.yaml";
  auto loaded = YamlMap::load_file(missing.string());
  ASSERT_FALSE(loaded);
  EXPECT_EQ(loaded.error().code, ErrorCode::kNotFound);
  EXPECT_EQ(loaded.error().message, missing.string() + ": does not exist");
  const auto link = dir_ / "link.yaml";
  std::filesystem::create_symlink(missing, link);
  auto dangling = YamlMap::load_file(link.string());
  ASSERT_FALSE(dangling);
  EXPECT_EQ(dangling.error().code, ErrorCode::kNotFound);
  EXPECT_EQ(dangling.error().message, fmt::format("{}: is a symbolic link to '{}', which does not exist",
                                                  link.string(), missing.string()));
}

TEST_F(YamlMapFiles, AFileLargerThanAnyConfigurationIsRefusedUnread) {
  const auto path = dir_ / "huge.yaml";
  {
    std::ofstream out(path);
    const std::string line = "# " + std::string(1022, 'x') + "\n";
    for (int i = 0; i < 1100; ++i) out << line;  // 1.1 MiB of comments: valid YAML, but no config
  }
  auto loaded = YamlMap::load_file(path.string());
  ASSERT_FALSE(loaded) << "a 1.1 MiB file was read as a configuration";
  EXPECT_EQ(loaded.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(loaded.error().message, path.string() + ": larger than 1048576 bytes: not a configuration file");
}

// The bound is exact, whatever the chunks the text is read in.
TEST(ReadAtMost, ReadsUpToTheBoundAndRefusesOneByteMore) {
  for (const std::size_t size : {std::size_t{0}, std::size_t{1}, std::size_t{4095}, std::size_t{4096},
                                 std::size_t{4097}, std::size_t{10000}}) {
    std::string content(size, 'a');
    for (std::size_t i = 0; i < size; ++i) content[i] = static_cast<char>('a' + i % 26);
    std::istringstream exact(content);
    const std::optional<std::string> read = read_at_most(exact, size);
    ASSERT_TRUE(read) << size;
    EXPECT_EQ(*read, content);
    std::istringstream roomy(content);
    EXPECT_EQ(read_at_most(roomy, size + 4096), content);
    if (size > 0) {
      std::istringstream over(content);
      EXPECT_FALSE(read_at_most(over, size - 1)) << size;
    }
  }
}

TEST_F(YamlMapFiles, AFileWithInvalidUtf8IsRefused) {
  const auto path = dir_ / "hub.yaml";
  std::ofstream(path) << "hub: dock_ecu\n# comment\nname: \xC0\xAF\n";
  auto loaded = YamlMap::load_file(path.string());
  ASSERT_FALSE(loaded);
  EXPECT_TRUE(loaded.error().message.starts_with(path.string() + ":3:7: not valid UTF-8 (byte 0xC0): "))
      << loaded.error().message;
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
