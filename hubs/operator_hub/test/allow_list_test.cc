// The allow-list: the format and its errors (file:line), hashes that match an independent
// SHA-256 (Python's hashlib made test/operators.list), and no badge in clear anywhere.
#include "allow_list.h"

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "alloc_counter.h"

namespace hubrt::operator_hub {
namespace {

const std::string kTestList = std::string(HUBRT_OPERATOR_HUB_DIR) + "/test/operators.list";
constexpr std::string_view kSalt = "salt 000102030405060708090a0b0c0d0e0f\n";
constexpr std::string_view kAnnaHash = "9ad4c64a7759c8d049ab050687fba59358a934c134d10c072ff23c6d27f9b62a";

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(AllowListTest, TheTestListLoadsWithItsOperators) {
  auto list = AllowList::load(kTestList);
  ASSERT_TRUE(list) << list.error().message;
  ASSERT_EQ(list->operators().size(), 2U);
  EXPECT_EQ(list->operators()[0].name, "Anna Svensson");
  EXPECT_EQ(list->operators()[1].name, "Bo Ek");
  EXPECT_EQ(list->operators()[0].line, 4);
}

TEST(AllowListTest, SaltedSha256MatchesAnIndependentImplementation) {
  auto list = AllowList::load(kTestList);
  ASSERT_TRUE(list);
  auto hasher = BadgeHasher::create();
  ASSERT_TRUE(hasher) << hasher.error().message;
  BadgeDigest digest{};
  ASSERT_TRUE(hasher->hash(list->salt(), "0004123456", digest));
  std::array<char, 64> hex{};
  to_hex(digest, hex);
  EXPECT_EQ(std::string_view(hex.data(), hex.size()), kAnnaHash);
  const AllowedOperator* found = list->find(digest);
  ASSERT_NE(found, nullptr);
  EXPECT_EQ(found->name, "Anna Svensson");
  ASSERT_TRUE(hasher->hash(list->salt(), "0004123457", digest));
  EXPECT_EQ(list->find(digest), nullptr);
}

TEST(AllowListTest, TheFileHoldsNoBadgeInClear) {
  const std::string text = file_text(kTestList);
  // The comment names the test badges on purpose; the entries must not.
  const std::string entries = text.substr(text.find("salt "));
  EXPECT_EQ(entries.find("0004123456"), std::string::npos);
  EXPECT_EQ(entries.find("A1B2C3D4"), std::string::npos);
}

TEST(AllowListTest, HashingAgainAllocatesNothing) {
  auto list = AllowList::load(kTestList);
  ASSERT_TRUE(list);
  auto hasher = BadgeHasher::create();
  ASSERT_TRUE(hasher);
  BadgeDigest digest{};
  ASSERT_TRUE(hasher->hash(list->salt(), "warm-up", digest));
  const hubrt::testing::AllocationScope scope;
  for (int i = 0; i < 10; ++i) {
    ASSERT_TRUE(hasher->hash(list->salt(), "0004123456", digest));
    EXPECT_NE(list->find(digest), nullptr);
  }
  EXPECT_EQ(scope.count(), 0U);
}

struct BrokenList {
  std::string_view name;
  std::string text;
  std::string_view expected;  // the message, after "<file>:"
};

class BrokenAllowListTest : public ::testing::TestWithParam<BrokenList> {};

TEST_P(BrokenAllowListTest, IsRefusedWithFileAndLine) {
  auto list = AllowList::parse(GetParam().text, "ops.list");
  ASSERT_FALSE(list);
  EXPECT_EQ(list.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(list.error().message, "ops.list:" + std::string(GetParam().expected));
}

const std::string kAnna = std::string(kAnnaHash) + " Anna\n";

INSTANTIATE_TEST_SUITE_P(
    Lists, BrokenAllowListTest,
    ::testing::Values(
        BrokenList{"NoSalt", "# nothing\n", "1: no salt line: the file starts with salt <32 hex digits>"},
        BrokenList{"OperatorBeforeSalt", kAnna,
                   "1: the file starts with its salt line: salt <32 hex digits>"},
        BrokenList{"ShortSalt", "salt 0011\n", "1: the salt is 32 hex digits (16 bytes)"},
        BrokenList{"TwoSalts", std::string(kSalt) + std::string(kSalt),
                   "2: a second salt line (the file has one salt)"},
        BrokenList{
            "BadgeInClear", std::string(kSalt) + "0004123456 Anna\n",
            "2: expected '<SHA-256 in hex (64 digits)> <name>' (enrol badges with operator-enrol add)"},
        BrokenList{"NoName", std::string(kSalt) + std::string(kAnnaHash) + "\n",
                   "2: an operator needs a name"},
        BrokenList{"ControlInName", std::string(kSalt) + std::string(kAnnaHash) + " An\x01na\n",
                   "2: a name must not hold control characters"},
        BrokenList{"NotUtf8", std::string(kSalt) + std::string(kAnnaHash) + " An\xffna\n",
                   "2: not valid UTF-8"},
        BrokenList{"SameName", std::string(kSalt) + kAnna + std::string(64, 'b') + " Anna\n",
                   "3: operator 'Anna' is already on line 2"},
        BrokenList{"SameBadge", std::string(kSalt) + kAnna + std::string(kAnnaHash) + " Bo\n",
                   "3: the same badge is already on line 2"}),
    [](const auto& list_info) { return std::string(list_info.param.name); });

TEST(AllowListTest, MissingFileSaysSo) {
  auto list = AllowList::load("/nonexistent/operators.list");
  ASSERT_FALSE(list);
  EXPECT_EQ(list.error().code, ErrorCode::kNotFound);
  EXPECT_NE(list.error().message.find("/nonexistent/operators.list: cannot read"), std::string::npos);
}

}  // namespace
}  // namespace hubrt::operator_hub
