// The station's PKI, made with OpenSSL's C API: two CAs (identity, permissions), one certificate
// and key per participant, and the governance and permissions documents signed by the
// permissions CA as S/MIME (what Cyclone's access control reads: SMIME_read_PKCS7 and
// PKCS7_verify(..., PKCS7_TEXT) in access_control_utils.c, Cyclone 0.10.2). Keys are ECDSA P-256,
// one of the two kinds Cyclone's authentication plugin accepts (auth_utils.c: RSA-2048 and
// EC prime256v1). Files: station_files.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/security/documents.h"

namespace hubrt::security {

struct Validity {
  std::int64_t not_before_unix = 0;
  std::int64_t not_after_unix = 0;
};

// Makes `dir` (and dir/private, 0700) and in it both CAs (certificates 0644, keys 0600 under
// private/) and the signed governance document.
// Errors: kInvalidArgument for an empty validity; kFailedPrecondition when `dir` already holds a
// CA (nothing is overwritten: rotate the CAs into a new folder); kIo naming the file that could not
// be written; kInternal with OpenSSL's errors.
Expected<void> init_station(const std::string& dir, const Validity& validity);

// Issues `identity`'s certificate (subject "CN=<identity>,O=hubrt station", signed by the
// identity CA) and key (0600), and its permissions document for `publish`/`subscribe` (DDS topic
// expressions) in the DDS domains `domains` (ascending, each once; empty: every domain, Grant)
// signed by the permissions CA; replaces an earlier identity of the same name (that is how a
// certificate is renewed).
// Errors: kInvalidArgument for a bad name or validity, or a domain above kLastDomainId or out of
// order; kNotFound when `dir` has no CA (run init); kIo / kInternal as init_station.
Expected<void> add_identity(const std::string& dir, const std::string& identity, const Validity& validity,
                            const std::vector<std::string>& publish,
                            const std::vector<std::string>& subscribe,
                            const std::vector<std::uint32_t>& domains = {});

// The certificate subject add_identity gives `identity`.
std::string identity_subject(const std::string& identity);

// `document` signed by the certificate and key as S/MIME (detached, text), as `openssl smime
// -sign -text` does. Errors: kInternal with OpenSSL's errors.
Expected<std::string> sign_document(const std::string& document, const std::string& cert_path,
                                    const std::string& key_path);

// The content of an S/MIME document if its signature verifies against the CA certificate at
// `ca_path` at `now_unix`. Errors: kInvalidArgument naming `what` and `path` with OpenSSL's
// reason; read errors as read_small_file.
Expected<std::string> verify_document(const std::string& path, const std::string& what,
                                      const std::string& ca_path, std::int64_t now_unix);

}  // namespace hubrt::security
