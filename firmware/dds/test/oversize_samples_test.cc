#include "hubrt/dds/oversize_samples.h"

#include <dds/dds.h>
#include <gtest/gtest.h>

namespace hubrt::dds {
namespace {

// The two discard warnings of Cyclone 0.10.2 src/core/ddsi/src/q_receive.c, drop_oversize, as
// they read once formatted.
TEST(OversizeSamples, RecognisesCyclonesDiscardWarnings) {
  EXPECT_TRUE(is_oversize_drop_message(
      "dropping oversize (16777228 > 65536) sample 7 from remote writer 1107a8e1:6c1f5a4e:e3d4a1cb:103 "
      "rt/dock/command/hub_msgs::msg::dds_::DockCommand_\n"));
  EXPECT_TRUE(
      is_oversize_drop_message("dropping oversize (70000 > 65536) SPDP sample 1 from remote writer "
                               "1107a8e1:6c1f5a4e:e3d4a1cb:100c2\n"));
  EXPECT_FALSE(is_oversize_drop_message("malformed packet received from vendor 1.16 state parse:data\n"));
  EXPECT_FALSE(is_oversize_drop_message("dropping"));
  EXPECT_FALSE(is_oversize_drop_message(""));
}

// Each TEST runs in its own process (gtest_discover_tests): the sink is installed here first.
TEST(OversizeSamples, CountsTheWarningsThroughCyclonesLogOnceInstalled) {
  EXPECT_FALSE(oversize_samples_counted());
  count_oversize_samples();
  count_oversize_samples();  // a second call changes nothing
  EXPECT_TRUE(oversize_samples_counted());
  EXPECT_EQ(oversize_samples_dropped(), 0u);
  // Through Cyclone's own logging entry point, as drop_oversize's DDS_CWARNING ends up.
  dds_log(DDS_LC_WARNING, __FILE__, __LINE__, "drop_oversize",
          "dropping oversize (%u > %u) sample %u from remote writer x rt/t/T\n", 1048588u, 65536u, 1u);
  dds_log(DDS_LC_WARNING, __FILE__, __LINE__, "drop_oversize",
          "dropping oversize (%u > %u) SPDP sample %u from remote writer x\n", 70000u, 65536u, 2u);
  EXPECT_EQ(oversize_samples_dropped(), 2u);
  // Other warnings and errors are passed on, not counted.
  dds_log(DDS_LC_WARNING, __FILE__, __LINE__, "f", "some other warning\n");
  dds_log(DDS_LC_ERROR, __FILE__, __LINE__, "f", "dropping oversize (but an error, not the warning)\n");
  EXPECT_EQ(oversize_samples_dropped(), 2u);
}

}  // namespace
}  // namespace hubrt::dds
