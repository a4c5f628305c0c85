// The start-up twin check's rule (StartupCheck, twin_rules.h) under manual time: it ends as soon
// as discovery has settled instead of always waiting its whole window, and still refuses a twin
// known only by the identity in its USER_DATA (SPDP, before any of its writers).
#include <gtest/gtest.h>

#include "hubrt/assembly/twin_rules.h"

namespace hubrt::assembly {
namespace {

using std::chrono::milliseconds;

constexpr Duration kWindow = milliseconds(300);
constexpr Duration kQuiet = milliseconds(15);

dds::WatchedParticipant participant(std::uint8_t first, std::string user_data) {
  dds::WatchedParticipant p;
  p.key.bytes[0] = first;
  p.user_data = std::move(user_data);
  return p;
}

class StartupCheckTest : public ::testing::Test {
 protected:
  Time at(int ms) const { return begin_ + milliseconds(ms); }
  Time begin_ = Time(std::chrono::seconds(100));
  StartupCheck check_{"/dock_ecu", begin_, kWindow, kQuiet};
};

TEST(HubUserData, CarriesTheStampAndTheIdentity) {
  const std::string text = hub_user_data(42, "/station", "dock_ecu");
  EXPECT_EQ(text, "hubrt.started_ns=42;hubrt.hub=/station/dock_ecu;");
  EXPECT_EQ(parse_start_stamp(text), 42);
  EXPECT_EQ(parse_hub_identity(text), "/station/dock_ecu");
  EXPECT_EQ(parse_hub_identity(hub_user_data(1, "", "dock_ecu")), "/dock_ecu");
  EXPECT_EQ(parse_hub_identity(start_stamp_user_data(42)), std::nullopt);  // an older hub
  EXPECT_EQ(parse_hub_identity("xhubrt.hub=/dock_ecu;"), std::nullopt);    // not at a pair boundary
  EXPECT_EQ(parse_hub_identity("hubrt.hub=/dock_ecu"), std::nullopt);      // unterminated
}

TEST_F(StartupCheckTest, AnEmptyDomainIsSettledAfterTheQuietTimeNotTheWindow) {
  EXPECT_EQ(check_.update({}, 0, 0, at(0)), StartupVerdict::kWait);
  EXPECT_EQ(check_.update({}, 0, 0, at(14)), StartupVerdict::kWait);
  EXPECT_EQ(check_.update({}, 0, 0, at(15)), StartupVerdict::kAlone);
}

TEST_F(StartupCheckTest, EachNewlyDiscoveredParticipantRestartsTheQuietTime) {
  const std::vector others = {participant(1, ""), participant(2, hub_user_data(5, "", "tool_ecu"))};
  EXPECT_EQ(check_.update({others[0]}, 1, 0, at(10)), StartupVerdict::kWait);
  EXPECT_EQ(check_.update(others, 2, 0, at(20)), StartupVerdict::kWait);
  EXPECT_EQ(check_.update(others, 2, 0, at(34)), StartupVerdict::kWait);
  EXPECT_EQ(check_.update(others, 2, 0, at(35)), StartupVerdict::kAlone);
}

TEST_F(StartupCheckTest, AnOlderHubWithoutIdentityMakesItWaitTheWholeWindow) {
  const std::vector others = {participant(1, start_stamp_user_data(5))};
  EXPECT_EQ(check_.update(others, 1, 0, at(1)), StartupVerdict::kWait);
  EXPECT_EQ(check_.update(others, 1, 0, at(200)), StartupVerdict::kWait);
  EXPECT_EQ(check_.update(others, 1, 0, at(300)), StartupVerdict::kAlone);
}

TEST_F(StartupCheckTest, AWriterOfThisHubsStatesIsATwinAtOnce) {
  EXPECT_EQ(check_.update({participant(1, "")}, 1, 1, at(2)), StartupVerdict::kTwin);
}

TEST_F(StartupCheckTest, AParticipantWithThisHubsIdentityIsATwinBeforeItsWritersArrive) {
  const std::vector others = {participant(7, hub_user_data(5, "", "dock_ecu"))};
  // Waits a little for its writers, to name them in the refusal...
  EXPECT_EQ(check_.update(others, 1, 0, at(2)), StartupVerdict::kWait);
  EXPECT_EQ(check_.update(others, 1, 1, at(4)), StartupVerdict::kTwin);
  EXPECT_TRUE(check_.twin_by_identity());
  EXPECT_EQ(check_.claimant().bytes[0], 7);
}

TEST_F(StartupCheckTest, ATwinKnownByIdentityIsRefusedEvenIfItsWritersNeverArrive) {
  const std::vector others = {participant(7, hub_user_data(5, "", "dock_ecu"))};
  EXPECT_EQ(check_.update(others, 1, 0, at(2)), StartupVerdict::kWait);
  // Never "alone" while a twin is known: quiet time and window both end in a refusal.
  EXPECT_EQ(check_.update(others, 1, 0, at(17)), StartupVerdict::kTwin);
}

TEST_F(StartupCheckTest, TheSameHubNameInAnotherNamespaceIsNoTwin) {
  const std::vector others = {participant(7, hub_user_data(5, "/other", "dock_ecu"))};
  EXPECT_EQ(check_.update(others, 1, 0, at(1)), StartupVerdict::kWait);
  EXPECT_EQ(check_.update(others, 1, 0, at(16)), StartupVerdict::kAlone);
}

// The check looks at discovery only now and then (hubd creates DDS entities meanwhile): a
// participant counts from when it was discovered, so the quiet time is not restarted late.
TEST_F(StartupCheckTest, ADiscoveryCountsFromWhenItHappenedNotFromWhenTheCheckLooked) {
  const std::vector others = {participant(1, "")};
  // Discovered at 2 ms, first looked at 9 ms: settled at 2 + 15, not 9 + 15.
  EXPECT_EQ(check_.update(others, 1, at(2), 0, at(9)), StartupVerdict::kWait);
  EXPECT_EQ(check_.decides_by(), at(17));
  EXPECT_EQ(check_.update(others, 1, at(2), 0, at(16)), StartupVerdict::kWait);
  EXPECT_EQ(check_.update(others, 1, at(2), 0, at(17)), StartupVerdict::kAlone);
}

TEST_F(StartupCheckTest, ADiscoveryTimeOutsideTheCheckIsClampedToIt) {
  const std::vector others = {participant(1, "")};
  // Before the check began (a stale stamp): counts from the begin, never earlier.
  EXPECT_EQ(check_.update(others, 1, begin_ - milliseconds(50), 0, at(1)), StartupVerdict::kWait);
  EXPECT_EQ(check_.decides_by(), at(15));
  // In the future of the look (clocks read in another order): counts from the look.
  EXPECT_EQ(check_.update({others[0], participant(2, "")}, 2, at(30), 0, at(5)), StartupVerdict::kWait);
  EXPECT_EQ(check_.decides_by(), at(20));
  EXPECT_EQ(check_.update({others[0], participant(2, "")}, 2, at(30), 0, at(19)), StartupVerdict::kWait);
  EXPECT_EQ(check_.update({others[0], participant(2, "")}, 2, at(30), 0, at(20)), StartupVerdict::kAlone);
}

TEST_F(StartupCheckTest, DecidesByIsWhenTheRuleCanFirstGiveAVerdict) {
  EXPECT_EQ(check_.decides_by(), at(15));  // before any look: an empty domain settles then
  const std::vector hub = {participant(1, hub_user_data(5, "", "tool_ecu"))};
  EXPECT_EQ(check_.update(hub, 1, at(3), 0, at(4)), StartupVerdict::kWait);
  EXPECT_EQ(check_.decides_by(), at(18));
  // An older hub without an identity: only the window ends the check.
  const std::vector older = {hub[0], participant(2, start_stamp_user_data(5))};
  EXPECT_EQ(check_.update(older, 2, at(6), 0, at(7)), StartupVerdict::kWait);
  EXPECT_EQ(check_.decides_by(), at(300));
}

TEST_F(StartupCheckTest, DecidesByAfterATwinsIdentityIsTheEndOfItsWaitForWriters) {
  const std::vector twin = {participant(7, hub_user_data(5, "", "dock_ecu"))};
  EXPECT_EQ(check_.update(twin, 1, at(1), 0, at(2)), StartupVerdict::kWait);
  EXPECT_EQ(check_.decides_by(), at(17));
  EXPECT_EQ(check_.update(twin, 1, at(1), 0, at(17)), StartupVerdict::kTwin);
}

// A twin known by identity alone has no name yet but its GUID: the refusal waits for its writer
// (topic, host, pid) up to kNamingGrace after the verdict, and not a moment once the writer is there.
TEST_F(StartupCheckTest, ARefusalByIdentityWaitsForTheTwinsWriterToNameItForTheGraceOnly) {
  const std::vector twin = {participant(7, hub_user_data(5, "", "dock_ecu"))};
  EXPECT_FALSE(check_.waits_for_name(0, at(1)));  // no verdict yet
  EXPECT_EQ(check_.update(twin, 1, at(1), 0, at(2)), StartupVerdict::kWait);
  EXPECT_FALSE(check_.waits_for_name(0, at(3)));  // still deciding: nothing to name
  EXPECT_EQ(check_.update(twin, 1, at(1), 0, at(17)), StartupVerdict::kTwin);
  EXPECT_TRUE(check_.twin_by_identity());
  const Duration grace = StartupCheck::kNamingGrace;
  EXPECT_TRUE(check_.waits_for_name(0, at(17)));
  EXPECT_TRUE(check_.waits_for_name(0, at(17) + grace - milliseconds(1)));
  EXPECT_FALSE(check_.waits_for_name(0, at(17) + grace));  // the grace is over: named by GUID
  EXPECT_FALSE(check_.waits_for_name(1, at(18)));          // its writer arrived: named now
  // A later update (the caller looked again) does not move the verdict's time.
  EXPECT_EQ(check_.update(twin, 1, at(1), 0, at(500)), StartupVerdict::kTwin);
  EXPECT_FALSE(check_.waits_for_name(0, at(17) + grace));
}

TEST_F(StartupCheckTest, ARefusalByAWriterHasItsNameAndDoesNotWait) {
  EXPECT_EQ(check_.update({}, 0, 1, at(1)), StartupVerdict::kTwin);
  EXPECT_FALSE(check_.twin_by_identity());
  EXPECT_FALSE(check_.waits_for_name(0, at(2)));
}

}  // namespace
}  // namespace hubrt::assembly
