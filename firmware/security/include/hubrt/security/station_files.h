// Where a station's DDS Security files live. One folder per station (made by `hubctl security
// init`, filled by `hubctl security add`), laid out so that a board gets a copy of the folder
// without private/ and without the other identities' files (docs/deploy.md, "Securing a station"):
//
//   <dir>/identity_ca.pem                the identity CA's certificate (authentication)
//   <dir>/permissions_ca.pem             the permissions CA's certificate (signs the documents)
//   <dir>/governance.xml, governance.p7s the domain's rules, and the same signed (S/MIME)
//   <dir>/<identity>.cert.pem            one identity's certificate, issued by the identity CA
//   <dir>/<identity>.key.pem             its private key (0600)
//   <dir>/<identity>.permissions.xml/.p7s what it may publish and subscribe, signed
//   <dir>/private/*_ca.key.pem           the CAs' private keys: stay on the machine that signs
#pragma once

#include <string>
#include <string_view>

#include "hubrt/base/status.h"

namespace hubrt::security {

// The files one participant (a hub, the planner, an observer) runs with.
struct Credentials {
  std::string identity_ca;     // PEM certificate
  std::string identity_cert;   // PEM certificate of the participant
  std::string private_key;     // PEM private key of the participant (unencrypted, 0600)
  std::string permissions_ca;  // PEM certificate
  std::string governance;      // S/MIME signed governance document
  std::string permissions;     // S/MIME signed permissions document
};

// The station folder's paths for `identity` (not checked for existence).
Credentials credentials_in(const std::string& dir, const std::string& identity);

std::string identity_ca_key_path(const std::string& dir);
std::string permissions_ca_key_path(const std::string& dir);

// An identity name is used in file names and as the certificate's common name:
// [A-Za-z][A-Za-z0-9_-]*, at most 64 characters.
// Errors: kInvalidArgument saying what is wrong with the name.
Expected<void> check_identity_name(std::string_view identity);

}  // namespace hubrt::security
