// The process's one Cyclone log sink (src/log_sink.h) serves three readers at once: the oversize
// count (oversize_samples.h), the security refusals (security_refusals.h) and the forwarding of
// every line to hubd's bounded log queue (forward_cyclone_log). Each gets every line it is for,
// and nothing of it reaches stderr while a forward is set: a stderr nobody reads must not hold a
// Cyclone thread or the cycle (issue 29), a refusal's rate-limited line included.
#include <mutex>
#include <string>

#include <dds/dds.h>
#include <gtest/gtest.h>

#include "hubrt/dds/oversize_samples.h"
#include "hubrt/dds/security_refusals.h"

namespace hubrt::dds {
namespace {

std::mutex g_mutex;
std::string g_forwarded;  // what the forward was given, line after line

void forward_to_string(std::string_view line) noexcept {
  const std::lock_guard lock(g_mutex);
  g_forwarded.append(line);
}

std::string forwarded() {
  const std::lock_guard lock(g_mutex);
  return g_forwarded;
}

constexpr const char* kOmg = "/build/cyclonedds-0.10.2/src/core/ddsi/src/ddsi_security_omg.c";

// Each TEST runs in its own process (gtest_discover_tests): the sink and the forward are this
// process's alone.
TEST(CycloneLogSink, EveryLineReachesTheCountsAndTheForwardNoneStderr) {
  count_oversize_samples();
  count_security_refusals();
  forward_cyclone_log(&forward_to_string);
  testing::internal::CaptureStderr();
  dds_log(DDS_LC_WARNING, __FILE__, __LINE__, "drop_oversize",
          "dropping oversize (%u > %u) sample %u from remote writer x rt/t/T\n", 70000u, 65536u, 1u);
  for (int i = 0; i < 2; ++i)
    dds_log(DDS_LC_WARNING, kOmg, 1, "q_omg_security_check_remote_writer_permissions",
            "Non secure remote writer %x:%x:%x:%x is not allowed.\n", 1u, 2u, 3u, 0x103u);
  dds_log(DDS_LC_ERROR, __FILE__, __LINE__, "f", "an ordinary error\n");
  forward_cyclone_log(nullptr);
  const std::string on_stderr = testing::internal::GetCapturedStderr();
  const std::string lines = forwarded();

  EXPECT_EQ(oversize_samples_dropped(), 1u);
  EXPECT_EQ(security_refusals().writers, 1u);
  EXPECT_EQ(security_refusals().participants, 1u);
  EXPECT_EQ(on_stderr, "") << "written past the forward";
  // Cyclone's lines whole (header, message, newline); the refusal as its one rate-limited line,
  // not Cyclone's line every time.
  EXPECT_NE(lines.find("dropping oversize (70000 > 65536) sample 1 from remote writer x rt/t/T\n"),
            std::string::npos)
      << lines;
  EXPECT_NE(lines.find("an ordinary error\n"), std::string::npos) << lines;
  EXPECT_NE(lines.find("DDS Security refused a remote writer: Non secure remote writer 1:2:3:103 is not "
                       "allowed.\n"),
            std::string::npos)
      << lines;
  EXPECT_EQ(lines.find("DDS Security refused a remote writer", lines.find("refused a remote writer") + 1),
            std::string::npos)
      << "the second refusal within 10 s is held back:\n"
      << lines;
}

}  // namespace
}  // namespace hubrt::dds
