// Reading Cyclone 0.10.2's log lines about refused peers (security_refusals.h), and counting them
// through Cyclone's own logging entry point once the sink is installed. The lines with real
// refused peers (no security, a foreign CA) are in tests/integration/station_security_test.cc.
#include "hubrt/dds/security_refusals.h"

#include <dds/dds.h>
#include <gtest/gtest.h>

namespace hubrt::dds {
namespace {

constexpr const char* kHandshake = "/build/cyclonedds-0.10.2/src/core/ddsi/src/ddsi_handshake.c";
constexpr const char* kMatch = "/build/cyclonedds-0.10.2/src/core/ddsi/src/ddsi_entity_match.c";
constexpr const char* kOmgSource = "/build/cyclonedds-0.10.2/src/core/ddsi/src/ddsi_security_omg.c";

TEST(SecurityRefusals, ClassifiesCyclonesLinesByFileFunctionAndMarker) {
  RefusalLine l = classify_security_log(
      kMatch, "handshake_end_cb",
      "handshake (lguid=1107a8e1:6c1f5a4e:e3d4a1cb:1c1 rguid=aa:bb0:c:1c1) failed: (8) Failed");
  EXPECT_EQ(l.what, RefusedWhat::kAuthentication);
  ASSERT_TRUE(l.has_guid);
  EXPECT_EQ(l.guid, (std::array<std::uint32_t, 4>{0xaa, 0xbb0, 0xc, 0x1c1}));

  l = classify_security_log(kOmgSource, "q_omg_security_check_remote_writer_permissions",
                            "Non secure remote writer 1:2:3:103 is not allowed.");
  EXPECT_EQ(l.what, RefusedWhat::kWriter);
  EXPECT_TRUE(l.has_guid);
  EXPECT_EQ(l.guid[3], 0x103u);

  l = classify_security_log(
      kHandshake, "begin_handshake_reply_impl",
      "Begin handshake reply failed: Certificate verification error: unable to get local "
      "issuer certificate(code: 0)");
  EXPECT_EQ(l.what, RefusedWhat::kAuthentication);
  EXPECT_FALSE(l.has_guid);

  EXPECT_EQ(
      classify_security_log(kOmgSource, "f", "Plugin does not allow remote participant 5:6:7:1c1: x").what,
      RefusedWhat::kParticipant);
  // Not refusals: a handshake that succeeded, an oversize drop, a look-alike file, a GUID cut short.
  EXPECT_EQ(
      classify_security_log(kMatch, "handshake_end_cb", "handshake (lguid=1:2:3:4 rguid=5:6:7:8) processed")
          .what,
      RefusedWhat::kNothing);
  EXPECT_EQ(classify_security_log("/src/core/ddsi/src/q_receive.c", "drop_oversize",
                                  "dropping oversize (70000 > 65536) sample 7 from remote writer 1:2:3:4")
                .what,
            RefusedWhat::kNothing);
  EXPECT_EQ(classify_security_log("/x/my_ddsi_handshake.c", "f", "anything").what, RefusedWhat::kNothing);
  l = classify_security_log(kOmgSource, "f", "Non secure remote writer 1:2 is not allowed.");
  EXPECT_EQ(l.what, RefusedWhat::kWriter);
  EXPECT_FALSE(l.has_guid);
  EXPECT_FALSE(classify_security_log(kOmgSource, "f", "Non secure remote writer 123456789:2:3:4").has_guid)
      << "more than 32 bits";
}

// Each TEST runs in its own process (gtest_discover_tests): the sink is installed here first.
TEST(SecurityRefusals, CountsDistinctPeersAndLogsRateLimited) {
  EXPECT_FALSE(security_refusals_counted());
  EXPECT_FALSE(
      detail::observe_security_log(kOmgSource, "f", "Non secure remote writer 1:2:3:103 is not allowed."))
      << "nothing is counted before the sink is installed";
  count_security_refusals();
  EXPECT_TRUE(security_refusals_counted());
  EXPECT_EQ(security_refusals().total(), 0u);
  testing::internal::CaptureStderr();
  // Through Cyclone's own logging entry point, as GVWARNING ends up.
  for (int i = 0; i < 3; ++i)
    dds_log(DDS_LC_WARNING, kOmgSource, 1, "q_omg_security_check_remote_writer_permissions",
            "Non secure remote writer %x:%x:%x:%x is not allowed.\n", 1u, 2u, 3u, 0x103u);
  dds_log(DDS_LC_WARNING, kOmgSource, 1, "q_omg_security_check_remote_writer_permissions",
          "Non secure remote writer %x:%x:%x:%x is not allowed.\n", 1u, 2u, 3u, 0x203u);
  dds_log(DDS_LC_WARNING, kHandshake, 1, "begin_handshake_reply_impl",
          "Begin handshake reply failed: %s(code: 0)\n",
          "Certificate verification error: unable to get local issuer certificate");
  dds_log(DDS_LC_WARNING, kOmgSource, 1, "f", "some other warning\n");
  const std::string logged = testing::internal::GetCapturedStderr();
  const SecurityRefusalCounts counts = security_refusals();
  EXPECT_EQ(counts.writers, 2u) << "two writers, one of them refused three times";
  EXPECT_EQ(counts.participants, 1u) << "both of one participant without security";
  EXPECT_EQ(counts.authentication, 1u);
  EXPECT_EQ(last_security_refusal(),
            "Begin handshake reply failed: Certificate verification error: unable to get local issuer "
            "certificate(code: 0)");
  // The first writer refusal is logged, the next three within 10 s are held back; the
  // authentication failure is a kind of its own; other messages pass unchanged.
  std::size_t writer_lines = 0;
  for (std::size_t at = 0;
       (at = logged.find("DDS Security refused a remote writer: ", at)) != std::string::npos; ++at)
    ++writer_lines;
  EXPECT_EQ(writer_lines, 1u) << logged;
  EXPECT_NE(
      logged.find("DDS Security refused a remote participant's authentication: Begin handshake reply failed: "
                  "Certificate verification error: unable to get local issuer certificate(code: 0)\n"),
      std::string::npos)
      << logged;
  EXPECT_NE(logged.find("some other warning"), std::string::npos) << logged;
  // The reason a peer can choose (its certificate's subject) reaches no log as control bytes.
  testing::internal::CaptureStderr();
  dds_log(DDS_LC_WARNING, kHandshake, 1, "f",
          "Process handshake failed: subject: /CN=\x1b[2J\xff(code: 1)\n");
  const std::string escaped = testing::internal::GetCapturedStderr();
  EXPECT_EQ(last_security_refusal(), "Process handshake failed: subject: /CN=?[2J?(code: 1)");
  EXPECT_EQ(escaped.find('\x1b'), std::string::npos) << escaped;
}

}  // namespace
}  // namespace hubrt::dds
