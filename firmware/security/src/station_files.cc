#include "hubrt/security/station_files.h"

#include <fmt/format.h>

namespace hubrt::security {

Credentials credentials_in(const std::string& dir, const std::string& identity) {
  Credentials files;
  files.identity_ca = dir + "/identity_ca.pem";
  files.permissions_ca = dir + "/permissions_ca.pem";
  files.governance = dir + "/governance.p7s";
  files.identity_cert = fmt::format("{}/{}.cert.pem", dir, identity);
  files.private_key = fmt::format("{}/{}.key.pem", dir, identity);
  files.permissions = fmt::format("{}/{}.permissions.p7s", dir, identity);
  return files;
}

std::string identity_ca_key_path(const std::string& dir) {
  return dir + "/private/identity_ca.key.pem";
}

std::string permissions_ca_key_path(const std::string& dir) {
  return dir + "/private/permissions_ca.key.pem";
}

Expected<void> check_identity_name(std::string_view identity) {
  constexpr std::size_t kMaxLength = 64;
  const auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  bool ok = !identity.empty() && identity.size() <= kMaxLength && alpha(identity.front());
  for (const char c : identity) {
    ok = ok && (alpha(c) || (c >= '0' && c <= '9') || c == '_' || c == '-');
  }
  if (!ok) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("'{}' is not an identity name: use up to {} letters, digits, '_' and '-', "
                                  "starting with a letter",
                                  identity, kMaxLength));
  }
  return {};
}

}  // namespace hubrt::security
