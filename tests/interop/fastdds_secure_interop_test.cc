// Secured interop: the Fast DDS planner with Fast DDS's builtin security plugins (PKI-DH,
// Access-Permissions, AES-GCM-GMAC) against hubd with the plugins Debian's Cyclone ships, both
// from one throwaway PKI made with openssl (make_test_pki.sh): discovery and liveliness
// protected, payload encrypted, unauthenticated participants refused (docs/interop.md).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/test_support/hub_process.h"

#include "fastdds_dock_planner.h"

namespace hubrt::interop {
namespace {

using hub_msgs::msg::DockState;
using std::chrono::milliseconds;
namespace fs = std::filesystem;

// Generous: a loaded 2-core machine; the security handshake adds several round trips.
constexpr auto kSecurePatience = milliseconds(30000);

// Cyclone takes "file:<path>" (and a PEM inline as "data:,..."); Fast DDS 2.9 refuses that
// ("Unsupported URI format", PKIDH.cpp) and wants "file://<path>".
std::string file_uri(const fs::path& path) {
  return "file:" + path.string();
}
std::string fastdds_file_uri(const fs::path& path) {
  return "file://" + path.string();
}

// Cyclone's <Security> element (Cyclone DDS 0.10 configuration, Domain/Security): the plugins
// by full path, since Debian installs them off the library path (HUBRT_CYCLONE_SECURITY_DIR).
std::string cyclone_security_xml(const fs::path& pki, const std::string& id) {
  const std::string lib = HUBRT_CYCLONE_SECURITY_DIR;
  return fmt::format(
      "<Security>"
      "<Authentication><Library path=\"{0}/libdds_security_auth.so\" initFunction=\"init_authentication\" "
      "finalizeFunction=\"finalize_authentication\"/>"
      "<IdentityCA>{1}</IdentityCA><IdentityCertificate>{2}</IdentityCertificate><PrivateKey>{3}</PrivateKey>"
      "</Authentication>"
      "<AccessControl><Library path=\"{0}/libdds_security_ac.so\" initFunction=\"init_access_control\" "
      "finalizeFunction=\"finalize_access_control\"/>"
      "<PermissionsCA>{1}</PermissionsCA><Governance>{4}</Governance><Permissions>{5}</Permissions>"
      "</AccessControl>"
      "<Cryptographic><Library path=\"{0}/libdds_security_crypto.so\" initFunction=\"init_crypto\" "
      "finalizeFunction=\"finalize_crypto\"/></Cryptographic>"
      "</Security>",
      lib, file_uri(pki / "ca_cert.pem"), file_uri(pki / (id + "_cert.pem")),
      file_uri(pki / (id + "_key.pem")), file_uri(pki / "governance.p7s"),
      file_uri(pki / ("permissions_" + id + ".p7s")));
}

// Fast DDS's security properties (Fast DDS documentation, "Security" / "Access control" /
// "Cryptographic plugin": dds.sec.auth.*, dds.sec.access.*, dds.sec.crypto.*).
ParticipantProperties fastdds_security_properties(const fs::path& pki, const std::string& id) {
  return {
      {"dds.sec.auth.plugin", "builtin.PKI-DH"},
      {"dds.sec.auth.builtin.PKI-DH.identity_ca", fastdds_file_uri(pki / "ca_cert.pem")},
      {"dds.sec.auth.builtin.PKI-DH.identity_certificate", fastdds_file_uri(pki / (id + "_cert.pem"))},
      {"dds.sec.auth.builtin.PKI-DH.private_key", fastdds_file_uri(pki / (id + "_key.pem"))},
      {"dds.sec.access.plugin", "builtin.Access-Permissions"},
      {"dds.sec.access.builtin.Access-Permissions.permissions_ca", fastdds_file_uri(pki / "ca_cert.pem")},
      {"dds.sec.access.builtin.Access-Permissions.governance", fastdds_file_uri(pki / "governance.p7s")},
      {"dds.sec.access.builtin.Access-Permissions.permissions",
       fastdds_file_uri(pki / ("permissions_" + id + ".p7s"))},
      {"dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC"},
  };
}

class FastDdsSecureInteropTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire_outside_ephemeral_ports();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    pki_ = fs::temp_directory_path() / fmt::format("hubrt-fastdds-pki-{}", getpid());
    fs::create_directories(pki_);
    auto make_pki =
        test_support::ChildProcess::start("/bin/sh", {std::string(HUBRT_INTEROP_DIR) + "/make_test_pki.sh",
                                                      pki_.string(), std::to_string(domain_->domain_id())});
    ASSERT_TRUE(make_pki) << make_pki.error().message;
    auto made = make_pki->wait(std::chrono::seconds(60));
    ASSERT_TRUE(made && made->exited_with(0)) << make_pki->stderr_text();
  }
  void TearDown() override {
    if (planner_) (void)planner_->stop_repeating();
    std::error_code ignored;
    fs::remove_all(pki_, ignored);
  }

  void start_hub() {
    // A source of its own after the domain's (Cyclone reads comma-separated sources in order):
    // the domain's configuration may hold several sources, one of them for another domain id.
    const std::string xml = domain_->cyclone_xml() + ",<CycloneDDS><Domain id=\"any\">" +
                            cyclone_security_xml(pki_, "hub") + "</Domain></CycloneDDS>";
    test_support::HubProcessOptions options;
    options.extra_env = {{"CYCLONEDDS_URI", xml}};
    auto hub = test_support::HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
  }

  std::optional<test_support::TestDomain> domain_;
  fs::path pki_;
  std::unique_ptr<FastDdsDockPlanner> planner_;
  std::optional<test_support::HubProcess> hub_;
};

TEST_F(FastDdsSecureInteropTest, AnAuthenticatedFastDdsPlannerReadsAndCommandsASecuredHub) {
  auto planner =
      FastDdsDockPlanner::create(domain_->domain_id(), DockNodeTypes::kCommandTopic,
                                 DockNodeTypes::kStateTopic, fastdds_security_properties(pki_, "planner"));
  ASSERT_TRUE(planner) << planner.error().message;
  planner_ = std::move(*planner);
  const auto started = std::chrono::steady_clock::now();
  start_hub();
  ASSERT_TRUE(planner_->wait_for_hub(kSecurePatience)) << planner_->match_report() << "\n" << hub_->output();
  std::printf("secured: hubd start, handshake and match took %.2f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  auto first = planner_->next_state(kSecurePatience);
  ASSERT_TRUE(first) << hub_->output();
  EXPECT_EQ(first->state.name(), "dock");
  planner_->start_repeating(dock_command("dock", "dock", "monitor"), milliseconds(50));
  auto fresh = planner_->wait_for_state([](const DockState& s) { return s.fresh_msg(); }, kSecurePatience);
  ASSERT_TRUE(fresh) << hub_->output();
  EXPECT_EQ(fresh->state.echo().action(), "monitor");
  EXPECT_EQ(fresh->state.header().lifecycle(), hub_msgs::msg::StateHeader_Constants::LIFECYCLE_OPERATIONAL);
}

// Beside an authenticated planner that works, a Fast DDS participant without security (the
// governance allows no unauthenticated participants) and one whose identity a different CA
// signed both match nothing, receive no State, and their commands actuate nothing.
TEST_F(FastDdsSecureInteropTest, UnauthenticatedAndUntrustedFastDdsPlannersSeeAndCommandNothing) {
  auto trusted =
      FastDdsDockPlanner::create(domain_->domain_id(), DockNodeTypes::kCommandTopic,
                                 DockNodeTypes::kStateTopic, fastdds_security_properties(pki_, "planner"));
  ASSERT_TRUE(trusted) << trusted.error().message;
  auto plain = FastDdsDockPlanner::create(domain_->domain_id(), DockNodeTypes::kCommandTopic,
                                          DockNodeTypes::kStateTopic);
  ASSERT_TRUE(plain) << plain.error().message;
  // A PKI of the same shape and names, from another CA.
  const fs::path rogue_pki = pki_ / "rogue";
  fs::create_directories(rogue_pki);
  auto make_rogue = test_support::ChildProcess::start(
      "/bin/sh", {std::string(HUBRT_INTEROP_DIR) + "/make_test_pki.sh", rogue_pki.string(),
                  std::to_string(domain_->domain_id())});
  ASSERT_TRUE(make_rogue) << make_rogue.error().message;
  auto made = make_rogue->wait(std::chrono::seconds(60));
  ASSERT_TRUE(made && made->exited_with(0)) << make_rogue->stderr_text();
  auto rogue = FastDdsDockPlanner::create(domain_->domain_id(), DockNodeTypes::kCommandTopic,
                                          DockNodeTypes::kStateTopic,
                                          fastdds_security_properties(rogue_pki, "planner"));
  ASSERT_TRUE(rogue) << rogue.error().message;
  start_hub();

  // The outsiders command all along; the trusted planner only reads.
  (*plain)->start_repeating(dock_command("dock", "dock", "monitor"), milliseconds(50));
  (*rogue)->start_repeating(dock_command("dock", "dock", "monitor"), milliseconds(50));
  ASSERT_TRUE((*trusted)->wait_for_hub(kSecurePatience)) << (*trusted)->match_report() << "\n"
                                                         << hub_->output();
  // 3 s of heartbeat, seen by the trusted planner: no State fresh, so no outsider's command took
  // effect, while the outsiders receive nothing at all.
  constexpr int kStates = 30;
  for (int i = 0; i < kStates; ++i) {
    auto state = (*trusted)->next_state(kSecurePatience);
    ASSERT_TRUE(state) << hub_->output();
    EXPECT_FALSE(state->state.fresh_msg()) << "an unauthenticated or untrusted command took effect";
  }
  EXPECT_FALSE((*plain)->next_state(milliseconds(0))) << (*plain)->match_report();
  EXPECT_FALSE((*rogue)->next_state(milliseconds(0))) << (*rogue)->match_report();
  EXPECT_FALSE((*plain)->wait_for_hub(milliseconds(0))) << (*plain)->match_report();
  EXPECT_FALSE((*rogue)->wait_for_hub(milliseconds(0))) << (*rogue)->match_report();
  (void)(*plain)->stop_repeating();
  (void)(*rogue)->stop_repeating();
}

}  // namespace
}  // namespace hubrt::interop
