// `hubd --realtime` where the system does not permit real-time scheduling: hubd refuses to start
// with exit status 2 and a message naming what is missing, before it opens a device or joins the
// network (issue 16, point 5). The permission is taken away the way a service without
// LimitRTPRIO= meets it: RLIMIT_RTPRIO 0 and no CAP_SYS_NICE.
#include <unistd.h>

#include <gtest/gtest.h>
#include <linux/capability.h>
#include <sys/prctl.h>
#include <sys/resource.h>

#include "hubrt/test_support/hub_process.h"

namespace hubrt::integration {
using test_support::run_hubd;
namespace {

using std::chrono::seconds;

// Takes real-time scheduling away from the children this test process starts: the soft and
// hard RLIMIT_RTPRIO to 0 (always permitted: lowering), and CAP_SYS_NICE out of the bounding set,
// so that a program exec'd by root no longer gets it (capabilities(7), "Capability bounding
// set"). Returns false when the capability could not be dropped yet is held (then the test cannot
// take the permission away, and says so).
bool drop_realtime_permission(std::string& why) {
  const rlimit none{0, 0};
  if (setrlimit(RLIMIT_RTPRIO, &none) != 0) {
    why = "setrlimit(RLIMIT_RTPRIO, 0) failed";
    return false;
  }
  if (prctl(PR_CAPBSET_DROP, CAP_SYS_NICE, 0, 0, 0) == 0) return true;
  // Without CAP_SETPCAP the bounding set cannot change; an unprivileged user has no CAP_SYS_NICE
  // to lose in the first place.
  if (geteuid() != 0) return true;
  why = "running as root without CAP_SETPCAP: CAP_SYS_NICE cannot be dropped";
  return false;
}

class HubdRealtime : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
  }
  std::optional<test_support::TestDomain> domain_;
};

TEST_F(HubdRealtime, IsRefusedWithExit2AndTheReasonWhereNotPermitted) {
  std::string why;
  if (!drop_realtime_permission(why)) GTEST_SKIP() << why;
  auto finished =
      run_hubd(*domain_, {"--board", "host-sim", "--hub", "dock_ecu", "--realtime", "--twin-check-ms", "0"},
               seconds(60));
  ASSERT_TRUE(finished) << finished.error().message;
  EXPECT_TRUE(finished->status.exited_with(2)) << finished->status.describe() << finished->output;
  EXPECT_NE(finished->output.find("cannot run under SCHED_FIFO at priority 40"), std::string::npos)
      << finished->output;
  EXPECT_NE(finished->output.find("RLIMIT_RTPRIO of at least 40, which is 0 here"), std::string::npos)
      << finished->output;
  EXPECT_EQ(finished->output.find("running hub"), std::string::npos) << "it must not have started";
}

TEST_F(HubdRealtime, APriorityOutsideSchedFifosRangeIsABadCommandLine) {
  auto finished = run_hubd(
      *domain_, {"--board", "host-sim", "--hub", "dock_ecu", "--realtime", "--realtime-priority", "100"},
      seconds(60));
  ASSERT_TRUE(finished) << finished.error().message;
  EXPECT_TRUE(finished->status.exited_with(2)) << finished->status.describe() << finished->output;
  EXPECT_NE(finished->output.find("--realtime-priority"), std::string::npos) << finished->output;
}

}  // namespace
}  // namespace hubrt::integration
