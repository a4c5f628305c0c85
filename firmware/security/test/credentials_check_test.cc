// The refusals a hub must give at start, before Cyclone: each names the file and the cause.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "hubrt/security/participant_security.h"
#include "hubrt/security/pki.h"

#include "security_test_support.h"

namespace hubrt::security {
namespace {

using test::kDay;
using test::kNow;
using test::TempFolder;
using test::year_around_now;

class CredentialsCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(init_station(station_.path(), year_around_now()));
    ASSERT_TRUE(
        add_identity(station_.path(), "dock_ecu", year_around_now(), {"rt/dock_ecu/*"}, {"rt/dock/command"}));
  }
  [[nodiscard]] Credentials files(const std::string& identity = "dock_ecu") const {
    return credentials_in(station_.path(), identity);
  }
  void expect_refused(const Credentials& credentials, std::int64_t now, const std::string& fragment) const {
    auto checked = check_credentials(credentials, now);
    ASSERT_FALSE(checked) << "accepted; expected: " << fragment;
    EXPECT_NE(checked.error().message.find(fragment), std::string::npos) << checked.error().message;
  }
  TempFolder station_;
};

TEST_F(CredentialsCheck, ValidCredentialsPass) {
  auto checked = check_credentials(files(), kNow);
  EXPECT_TRUE(checked) << checked.error().message;
}

TEST_F(CredentialsCheck, ExpiredIdentityIsRefusedWithItsDate) {
  ASSERT_TRUE(add_identity(station_.path(), "old", {kNow - 60 * kDay, kNow - 30 * kDay}, {}, {"rt/*"}));
  expect_refused(files("old"), kNow, "old.cert.pem has expired: valid until 2025-12-02 00:00:00 UTC");
  auto checked = check_credentials(files("old"), kNow);
  EXPECT_EQ(checked.error().code, ErrorCode::kFailedPrecondition);
}

// What hubd logs and hubctl names when no peer authenticates: the certificate and the CA it needs.
TEST_F(CredentialsCheck, DescribesTheIdentityAndItsCa) {
  const std::string text = describe_identity(files());
  EXPECT_EQ(text.rfind("certificate ", 0), 0U) << text;
  EXPECT_NE(text.find("CN=dock_ecu"), std::string::npos) << text;
  EXPECT_NE(text.find(files().identity_cert + ", valid until "), std::string::npos) << text;
  EXPECT_NE(text.find(" of identity CA "), std::string::npos) << text;
  EXPECT_NE(text.find("(" + files().identity_ca + ")"), std::string::npos) << text;
  Credentials missing = files();
  missing.identity_ca = station_.path() + "/nothing.pem";
  EXPECT_NE(describe_identity(missing).find("nothing.pem (unreadable)"), std::string::npos);
}

TEST_F(CredentialsCheck, NotYetValidIdentityIsRefused) {
  ASSERT_TRUE(add_identity(station_.path(), "early", {kNow + kDay, kNow + 30 * kDay}, {}, {"rt/*"}));
  expect_refused(files("early"), kNow, "is not valid yet: valid from 2026-01-02");
}

TEST_F(CredentialsCheck, IdentityOfAnotherStationIsUntrusted) {
  TempFolder other;
  ASSERT_TRUE(init_station(other.path(), year_around_now()));
  ASSERT_TRUE(add_identity(other.path(), "dock_ecu", year_around_now(), {}, {"rt/*"}));
  Credentials mixed = files();
  mixed.identity_cert = credentials_in(other.path(), "dock_ecu").identity_cert;
  mixed.private_key = credentials_in(other.path(), "dock_ecu").private_key;
  expect_refused(mixed, kNow, "is not trusted by the station's identity CA");
}

TEST_F(CredentialsCheck, KeyOfAnotherIdentityIsRefused) {
  ASSERT_TRUE(add_identity(station_.path(), "planner", year_around_now(), {}, {"rt/*"}));
  Credentials mixed = files();
  mixed.private_key = files("planner").private_key;
  expect_refused(mixed, kNow, "does not belong to the identity certificate");
}

TEST_F(CredentialsCheck, TamperedPermissionsAreRefused) {
  const std::string path = files().permissions;
  std::string text;
  {
    std::ifstream in(path);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto at = text.find("rt/dock/command");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 15, "rt/*/command///");
  std::ofstream(path) << text;
  expect_refused(files(), kNow, "is not signed by the permissions CA");
}

TEST_F(CredentialsCheck, MissingFileIsNamed) {
  std::filesystem::remove(files().identity_cert);
  auto checked = check_credentials(files(), kNow);
  ASSERT_FALSE(checked);
  EXPECT_EQ(checked.error().code, ErrorCode::kNotFound);
  EXPECT_NE(checked.error().message.find("dock_ecu.cert.pem"), std::string::npos);
}

TEST_F(CredentialsCheck, ExpiredCaIsRefused) {
  expect_refused(files(), kNow + 400 * kDay, "identity CA certificate");
}

}  // namespace
}  // namespace hubrt::security
