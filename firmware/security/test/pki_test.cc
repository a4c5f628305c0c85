#include "hubrt/security/pki.h"

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "hubrt/security/participant_security.h"
#include "hubrt/security/station_files.h"

#include "security_test_support.h"

namespace hubrt::security {
namespace {

using test::kNow;
using test::TempFolder;
using test::year_around_now;

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

unsigned mode_of(const std::string& path) {
  struct stat info {};
  EXPECT_EQ(::stat(path.c_str(), &info), 0) << path;
  return info.st_mode & 0777U;
}

TEST(StationPki, InitMakesBothCasAndSignedGovernanceKeysPrivate) {
  TempFolder folder;
  const std::string dir = folder.path() + "/station";
  ASSERT_TRUE(init_station(dir, year_around_now()));
  EXPECT_EQ(mode_of(identity_ca_key_path(dir)), 0600U);
  EXPECT_EQ(mode_of(permissions_ca_key_path(dir)), 0600U);
  EXPECT_EQ(mode_of(dir + "/private"), 0700U);
  const std::string governance = read(dir + "/governance.xml");
  EXPECT_NE(governance.find("<allow_unauthenticated_participants>false"), std::string::npos);
  EXPECT_NE(governance.find("<discovery_protection_kind>ENCRYPT"), std::string::npos);
  EXPECT_NE(governance.find("<liveliness_protection_kind>ENCRYPT"), std::string::npos);
  EXPECT_NE(governance.find("<data_protection_kind>ENCRYPT"), std::string::npos);
  EXPECT_NE(governance.find("<topic_expression>rt/*/command"), std::string::npos);
  auto verified = verify_document(dir + "/governance.p7s", "governance", dir + "/permissions_ca.pem", kNow);
  ASSERT_TRUE(verified) << verified.error().message;
  EXPECT_EQ(*verified, governance);
}

TEST(StationPki, InitRefusesToOverwriteAStation) {
  TempFolder folder;
  ASSERT_TRUE(init_station(folder.path(), year_around_now()));
  const std::string before = read(folder.path() + "/identity_ca.pem");
  auto again = init_station(folder.path(), year_around_now());
  ASSERT_FALSE(again);
  EXPECT_EQ(again.error().code, ErrorCode::kFailedPrecondition);
  EXPECT_NE(again.error().message.find("already holds a station CA"), std::string::npos);
  EXPECT_EQ(read(folder.path() + "/identity_ca.pem"), before);
}

TEST(StationPki, AddIssuesCertificateKeyAndSignedPermissions) {
  TempFolder folder;
  ASSERT_TRUE(init_station(folder.path(), year_around_now()));
  ASSERT_TRUE(add_identity(folder.path(), "dock_ecu", year_around_now(), {"rt/dock_ecu/dock/state"},
                           {"rt/dock/command"}));
  const Credentials files = credentials_in(folder.path(), "dock_ecu");
  EXPECT_EQ(mode_of(files.private_key), 0600U);
  auto permissions = verify_document(files.permissions, "permissions", files.permissions_ca, kNow);
  ASSERT_TRUE(permissions) << permissions.error().message;
  EXPECT_NE(permissions->find("<subject_name>CN=dock_ecu,O=hubrt station</subject_name>"), std::string::npos);
  EXPECT_NE(permissions->find("<publish><topics>\n          <topic>rt/dock_ecu/dock/state</topic>"),
            std::string::npos);
  EXPECT_NE(permissions->find("<topic>rt/dock/command</topic>"), std::string::npos);
  EXPECT_NE(permissions->find("<default>DENY</default>"), std::string::npos);
  EXPECT_TRUE(check_credentials(files, kNow));
}

TEST(StationPki, ObserverPermissionsHaveNoPublishRule) {
  Grant grant;
  grant.name = "observer";
  grant.subject = identity_subject("observer");
  grant.not_before_unix = kNow;
  grant.not_after_unix = kNow + 1;
  grant.subscribe = {"rt/*"};
  const std::string xml = permissions_xml(grant);
  EXPECT_EQ(xml.find("<publish>"), std::string::npos);
  EXPECT_NE(xml.find("<subscribe><topics>"), std::string::npos);
  EXPECT_NE(xml.find("<not_before>2026-01-01T00:00:00</not_before>"), std::string::npos);
}

// A plant with one domain per station (docs/plant.md): a station's identity may join its own
// station's domain only; the plant's tools one identity for all of them.
TEST(StationPki, AnIdentityMayJoinTheDomainsItWasGrantedAndNoOthers) {
  TempFolder folder;
  ASSERT_TRUE(init_station(folder.path(), year_around_now()));
  const auto grant_of = [&](const std::string& identity) {
    const Credentials files = credentials_in(folder.path(), identity);
    auto permissions = verify_document(files.permissions, "permissions", files.permissions_ca, kNow);
    EXPECT_TRUE(permissions) << permissions.error().message;
    return permissions ? *permissions : std::string();
  };
  ASSERT_TRUE(add_identity(folder.path(), "s3_dock_ecu", year_around_now(), {}, {"rt/*"}, {13}));
  EXPECT_NE(grant_of("s3_dock_ecu").find("<domains><id>13</id></domains>"), std::string::npos);
  ASSERT_TRUE(add_identity(folder.path(), "plant_tools", year_around_now(), {}, {"rt/*"}, {10, 11, 12, 20}));
  EXPECT_NE(grant_of("plant_tools")
                .find("<domains><id_range><min>10</min><max>12</max></id_range><id>20</id></domains>"),
            std::string::npos);
  // Without domains: every domain the governance covers, as before.
  ASSERT_TRUE(add_identity(folder.path(), "planner", year_around_now(), {}, {"rt/*"}));
  EXPECT_NE(grant_of("planner").find("<domains><id_range><min>0</min><max>230</max></id_range></domains>"),
            std::string::npos);
}

TEST(StationPki, RefusesADomainSecurityCannotCoverOrOutOfOrder) {
  TempFolder folder;
  ASSERT_TRUE(init_station(folder.path(), year_around_now()));
  auto above = add_identity(folder.path(), "planner", year_around_now(), {}, {"rt/*"}, {10, 231});
  ASSERT_FALSE(above);
  EXPECT_EQ(above.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(above.error().message.find("domain 231: DDS Security covers domains 0 to 230"), std::string::npos)
      << above.error().message;
  EXPECT_FALSE(add_identity(folder.path(), "planner", year_around_now(), {}, {"rt/*"}, {12, 11}));
  EXPECT_FALSE(add_identity(folder.path(), "planner", year_around_now(), {}, {"rt/*"}, {12, 12}));
  EXPECT_FALSE(std::ifstream(credentials_in(folder.path(), "planner").permissions)) << "nothing written";
}

TEST(StationPki, AddWithoutInitSaysToInit) {
  TempFolder folder;
  auto added = add_identity(folder.path(), "planner", year_around_now(), {}, {"rt/*"});
  ASSERT_FALSE(added);
  EXPECT_EQ(added.error().code, ErrorCode::kNotFound);
  EXPECT_NE(added.error().message.find("hubctl security init"), std::string::npos);
}

TEST(StationPki, RefusesBadNamesAndEmptyValidity) {
  TempFolder folder;
  ASSERT_TRUE(init_station(folder.path(), year_around_now()));
  for (const char* name : {"", "../x", "a b", "9lives", "dock/ecu"}) {
    auto added = add_identity(folder.path(), name, year_around_now(), {}, {});
    ASSERT_FALSE(added) << name;
    EXPECT_EQ(added.error().code, ErrorCode::kInvalidArgument) << name;
  }
  EXPECT_FALSE(add_identity(folder.path(), "planner", {kNow, kNow}, {}, {}));
}

TEST(CycloneSecurityXml, NamesThePluginsByFullPathAndEveryFile) {
  TempFolder plugins;
  for (const char* name : {"libdds_security_auth.so", "libdds_security_ac.so", "libdds_security_crypto.so"}) {
    std::ofstream(plugins.path() + "/" + name) << "";
  }
  const Credentials files = credentials_in("/etc/hubrt/security", "dock_ecu");
  auto xml = cyclone_security_xml(files, plugins.path());
  ASSERT_TRUE(xml) << xml.error().message;
  EXPECT_NE(xml->find("<Library path=\"" + plugins.path() +
                      "/libdds_security_auth.so\" "
                      "initFunction=\"init_authentication\""),
            std::string::npos);
  EXPECT_NE(
      xml->find("<IdentityCertificate>file:/etc/hubrt/security/dock_ecu.cert.pem</IdentityCertificate>"),
      std::string::npos);
  EXPECT_NE(xml->find("<Permissions>file:/etc/hubrt/security/dock_ecu.permissions.p7s</Permissions>"),
            std::string::npos);
  auto missing = cyclone_security_xml(files, plugins.path() + "/nowhere");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("libdds_security_auth.so not found"), std::string::npos);
}

TEST(CycloneSecurityXml, DefaultPluginFolderIsDebiansMultiarchOne) {
  EXPECT_NE(plugin_folder().find("libddsc0debian"), std::string::npos);
}

}  // namespace
}  // namespace hubrt::security
