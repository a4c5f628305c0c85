#include <cstdlib>
#include <ctime>

#include <fmt/format.h>
#include <sys/stat.h>

#include "hubrt/security/documents.h"
#include "hubrt/security/participant_security.h"

namespace hubrt::security {
namespace {

std::string file_uri(const std::string& path) {
  return "file:" + xml_escape(path);
}

std::string library(const std::string& path, const char* init, const char* finalize) {
  return fmt::format(R"(<Library path="{}" initFunction="{}" finalizeFunction="{}"/>)", xml_escape(path),
                     init, finalize);
}

}  // namespace

std::string plugin_folder() {
  // NOLINTNEXTLINE(concurrency-mt-unsafe): documented as reading the environment.
  const char* folder = std::getenv("HUBRT_DDS_SECURITY_PLUGINS");
  if (folder != nullptr && *folder != '\0') return folder;
  return HUBRT_DDS_SECURITY_PLUGIN_DIR;
}

Expected<std::string> cyclone_security_xml(const Credentials& files, const std::string& plugins) {
  const std::string auth = plugins + "/libdds_security_auth.so";
  const std::string access = plugins + "/libdds_security_ac.so";
  const std::string crypto = plugins + "/libdds_security_crypto.so";
  for (const std::string& path : {auth, access, crypto}) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) {
      return make_error(ErrorCode::kNotFound,
                        fmt::format("DDS Security plugin {} not found (Debian's libddsc0debian ships them; "
                                    "HUBRT_DDS_SECURITY_PLUGINS names another folder)",
                                    path));
    }
  }
  return fmt::format(
      "<CycloneDDS><Domain id=\"any\"><Security>"
      "<Authentication>{}<IdentityCA>{}</IdentityCA><IdentityCertificate>{}</IdentityCertificate>"
      "<PrivateKey>{}</PrivateKey></Authentication>"
      "<AccessControl>{}<PermissionsCA>{}</PermissionsCA><Governance>{}</Governance>"
      "<Permissions>{}</Permissions></AccessControl>"
      "<Cryptographic>{}</Cryptographic>"
      "</Security></Domain></CycloneDDS>",
      library(auth, "init_authentication", "finalize_authentication"), file_uri(files.identity_ca),
      file_uri(files.identity_cert), file_uri(files.private_key),
      library(access, "init_access_control", "finalize_access_control"), file_uri(files.permissions_ca),
      file_uri(files.governance), file_uri(files.permissions),
      library(crypto, "init_crypto", "finalize_crypto"));
}

Expected<std::string> secure_participant_xml(const Credentials& files, std::int64_t now_unix) {
  if (auto ok = check_credentials(files, now_unix); !ok) return std::move(ok).error();
  return cyclone_security_xml(files, plugin_folder());
}

}  // namespace hubrt::security

namespace hubrt::security {

Expected<std::string> security_xml_for(const SecurityChoice& choice, std::int64_t now_unix) {
  if (auto ok = check_identity_name(choice.identity); !ok) return std::move(ok).error();
  auto xml = secure_participant_xml(credentials_in(choice.dir, choice.identity), now_unix);
  if (!xml) {
    Error error = std::move(xml).error();
    error.message = fmt::format("DDS Security identity '{}' refused: {}", choice.identity, error.message);
    return error;
  }
  return xml;
}

std::string with_security(const std::string& cyclone_xml, const std::string& security_xml) {
  std::string sources = cyclone_xml;
  if (sources.empty()) {
    // NOLINTNEXTLINE(concurrency-mt-unsafe): documented as reading the environment.
    const char* uri = std::getenv("CYCLONEDDS_URI");
    if (uri != nullptr) sources = uri;
  }
  if (!sources.empty()) sources += ',';
  return sources + security_xml;
}

}  // namespace hubrt::security
