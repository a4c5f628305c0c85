// --domain as the plant-wide tools take it: what would break is a range read wrong (a station
// left out, or a domain joined that is not the plant's), an id Cyclone's ports cannot take
// accepted, a typo such as 0-232 starting 233 domain instances, or an id joined twice.
#include "domain_set.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace hubrt::hubctl {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::vector<std::uint32_t> ids(std::string_view text) {
  auto parsed = parse_domain_set(text);
  EXPECT_TRUE(parsed) << text << ": " << parsed.error().message;
  return parsed ? *parsed : std::vector<std::uint32_t>{};
}

std::string error_of(std::string_view text) {
  auto parsed = parse_domain_set(text);
  EXPECT_FALSE(parsed) << "accepted: " << text;
  if (parsed) return "";
  EXPECT_EQ(parsed.error().code, ErrorCode::kInvalidArgument);
  return parsed.error().message;
}

TEST(DomainSet, ReadsOneIdRangesAndListsInAscendingOrder) {
  EXPECT_THAT(ids("7"), ElementsAre(7U));
  EXPECT_THAT(ids("10-13"), ElementsAre(10U, 11U, 12U, 13U));
  EXPECT_THAT(ids("20, 3,5-6"), ElementsAre(3U, 5U, 6U, 20U));
  EXPECT_THAT(ids("4-4"), ElementsAre(4U));
  EXPECT_THAT(ids("0,232"), ElementsAre(0U, 232U));
  EXPECT_EQ(ids("10-41").size(), 32U);
}

TEST(DomainSet, RefusesWhatIsNotASetOfDomainIdsNamingThePart) {
  EXPECT_THAT(error_of(""), HasSubstr("no domain id"));
  EXPECT_THAT(error_of("  "), HasSubstr("no domain id"));
  EXPECT_THAT(error_of("10,,11"), HasSubstr("empty part"));
  EXPECT_THAT(error_of("10,"), HasSubstr("empty part"));
  EXPECT_THAT(error_of("ten"), HasSubstr("'ten' is not a domain id"));
  EXPECT_THAT(error_of("-3"), HasSubstr("is not a domain id"));
  EXPECT_THAT(error_of("+3"), HasSubstr("'+3' is not a domain id"));
  EXPECT_THAT(error_of("3-"), HasSubstr("'' is not a domain id"));
  EXPECT_THAT(error_of("1 0"), HasSubstr("'1 0' is not a domain id"));
  EXPECT_THAT(error_of("12-10"), HasSubstr("ends before it begins"));
  EXPECT_THAT(error_of("233"), HasSubstr("above 232"));
  EXPECT_THAT(error_of("230-240"), HasSubstr("above 232"));
  EXPECT_THAT(error_of("99999999999"), HasSubstr("above 232"));
  EXPECT_THAT(error_of("10-12,12"), HasSubstr("domain 12 is named twice"));
  EXPECT_THAT(error_of("0-232"), HasSubstr("more than 64 domains"));
  EXPECT_THAT(error_of("0-63,100"), HasSubstr("more than 64 domains"));
  EXPECT_EQ(ids("0-63").size(), kMaxPlantDomains);
}

TEST(DomainSet, FormatsTheIdsBackAsTheParserReadsThem) {
  EXPECT_EQ(format_domain_set({10, 11, 12, 20}), "10-12,20");
  EXPECT_EQ(format_domain_set({5}), "5");
  EXPECT_EQ(format_domain_set({}), "");
  EXPECT_EQ(format_domain_set({1, 3, 4}), "1,3-4");
  for (const char* text : {"10-41", "3,5,7-9", "0,232"}) EXPECT_EQ(format_domain_set(ids(text)), text);
}

}  // namespace
}  // namespace hubrt::hubctl
