// When hubctl says authentication failed instead of "nobody reads" (issue 34 point 3).
#include "peer_authentication.h"

#include <gtest/gtest.h>

namespace hubrt::hubctl {
namespace {

const std::string kIdentity =
    "'planner' with certificate CN=planner (p.pem) of identity CA CN=other (ca.pem)";
const std::string kReason =
    "Begin handshake reply failed: Certificate not valid: error: unable to get local issuer "
    "certificate(code: 200)";

TEST(AuthenticationProblem, SecuredWithPeersThatShowNoTopic) {
  // This side replied to a handshake and refused the peer's certificate: Cyclone's reason.
  auto said = authentication_problem(true, kIdentity, {0, 0, 0, 3}, kReason, {1, 0});
  ASSERT_TRUE(said);
  EXPECT_EQ(*said,
            "authentication failed: 1 participant(s) on the domain, none authenticated; Cyclone: " + kReason +
                ". This participant is " + kIdentity +
                ": peers authenticate it only when their identity CA is that one, and it them only when "
                "theirs is");
  // This side asked and the peer never answered: no reason in its own log.
  said = authentication_problem(true, kIdentity, {}, "", {2, 0});
  ASSERT_TRUE(said);
  EXPECT_NE(said->find("2 participant(s) on the domain, none authenticated; Cyclone: no handshake completed"),
            std::string::npos)
      << *said;
}

TEST(AuthenticationProblem, NotWhyNobodyReads) {
  EXPECT_FALSE(authentication_problem(true, kIdentity, {}, "", {0, 0})) << "nobody there at all";
  EXPECT_FALSE(authentication_problem(true, kIdentity, {0, 0, 0, 5}, kReason, {3, 1}))
      << "a peer showed topics: it authenticated, the topic just has no reader";
  EXPECT_FALSE(authentication_problem(false, "", {}, "", {2, 2}));
  EXPECT_FALSE(authentication_problem(false, "", {}, "", {1, 0}))
      << "without security, a participant with no topic may be anything (a tool, an observer)";
}

}  // namespace
}  // namespace hubrt::hubctl
