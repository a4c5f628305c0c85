// Making the station's CAs and identities with OpenSSL's C API.
#include "hubrt/security/pki.h"

#include <array>
#include <cerrno>
#include <cstring>
#include <tuple>

#include <fmt/format.h>
#include <openssl/bn.h>
#include <openssl/ec.h>
#include <openssl/rand.h>
#include <openssl/x509v3.h>
#include <sys/stat.h>

#include "hubrt/security/station_files.h"

#include "openssl_util.h"

namespace hubrt::security {
namespace {

using detail::Cert;
using detail::Key;
using detail::openssl_errors;

constexpr unsigned kPublicMode = 0644;
constexpr unsigned kPrivateMode = 0600;
constexpr const char* kOrganization = "hubrt station";

Error openssl_failure(const std::string& doing) {
  return make_error(ErrorCode::kInternal, fmt::format("cannot {}: {}", doing, openssl_errors()));
}

Expected<void> make_folder(const std::string& path, unsigned mode) {
  if (::mkdir(path.c_str(), mode) != 0 && errno != EEXIST) {
    return make_error(ErrorCode::kIo,
                      fmt::format("cannot make the folder {}: {}", path, std::strerror(errno)));
  }
  return {};
}

Expected<void> check_validity(const Validity& validity) {
  if (validity.not_after_unix <= validity.not_before_unix) {
    return make_error(ErrorCode::kInvalidArgument, "the validity ends before it starts");
  }
  return {};
}

Expected<void> check_domains(const std::vector<std::uint32_t>& domains) {
  for (std::size_t i = 0; i < domains.size(); ++i) {
    if (domains[i] > static_cast<std::uint32_t>(kLastDomainId)) {
      return make_error(
          ErrorCode::kInvalidArgument,
          fmt::format("domain {}: DDS Security covers domains {} to {} (Cyclone's access control "
                      "refuses a document naming a higher one)",
                      domains[i], kFirstDomainId, kLastDomainId));
    }
    if (i > 0 && domains[i] <= domains[i - 1]) {
      return make_error(
          ErrorCode::kInvalidArgument,
          fmt::format("domains {} and {}: not ascending, or named twice", domains[i - 1], domains[i]));
    }
  }
  return {};
}

bool add_extension(X509* cert, X509* issuer, int nid, const char* value) {
  X509V3_CTX ctx;
  X509V3_set_ctx(&ctx, issuer, cert, nullptr, nullptr, 0);
  X509_EXTENSION* extension = X509V3_EXT_conf_nid(nullptr, &ctx, nid, value);
  if (extension == nullptr) return false;
  const bool ok = X509_add_ext(cert, extension, -1) == 1;
  X509_EXTENSION_free(extension);
  return ok;
}

bool set_random_serial(X509* cert) {
  std::array<unsigned char, 16> bytes{};
  if (RAND_bytes(bytes.data(), static_cast<int>(bytes.size())) != 1) return false;
  bytes[0] &= 0x7f;  // positive (RFC 5280 §4.1.2.2)
  BIGNUM* number = BN_bin2bn(bytes.data(), static_cast<int>(bytes.size()), nullptr);
  const bool ok = number != nullptr && BN_to_ASN1_INTEGER(number, X509_get_serialNumber(cert)) != nullptr;
  BN_free(number);
  return ok;
}

struct Issued {
  Cert cert;
  Key key;
};

// A new P-256 key and its certificate for `common_name`, signed by `issuer` (self-signed when null).
Expected<Issued> issue(const std::string& common_name, const Validity& validity, bool is_ca,
                       X509* issuer_cert, EVP_PKEY* issuer_key) {
  Key key(EVP_EC_gen("P-256"));
  Cert cert(X509_new());
  if (!key || !cert) return openssl_failure("make a key");
  X509_NAME* name = X509_get_subject_name(cert.get());
  const auto* cn = reinterpret_cast<const unsigned char*>(common_name.c_str());
  const auto* org = reinterpret_cast<const unsigned char*>(kOrganization);
  const bool self_signed = issuer_cert == nullptr;
  bool ok = X509_set_version(cert.get(), 2) == 1 && set_random_serial(cert.get()) &&
            ASN1_TIME_set(X509_getm_notBefore(cert.get()), static_cast<time_t>(validity.not_before_unix)) !=
                nullptr &&
            ASN1_TIME_set(X509_getm_notAfter(cert.get()), static_cast<time_t>(validity.not_after_unix)) !=
                nullptr &&
            X509_NAME_add_entry_by_txt(name, "CN", MBSTRING_UTF8, cn, -1, -1, 0) == 1 &&
            X509_NAME_add_entry_by_txt(name, "O", MBSTRING_UTF8, org, -1, -1, 0) == 1 &&
            X509_set_issuer_name(cert.get(), self_signed ? name : X509_get_subject_name(issuer_cert)) == 1 &&
            X509_set_pubkey(cert.get(), key.get()) == 1;
  X509* signer_cert = self_signed ? cert.get() : issuer_cert;
  ok = ok && add_extension(cert.get(), signer_cert, NID_subject_key_identifier, "hash") &&
       add_extension(cert.get(), signer_cert, NID_authority_key_identifier, "keyid:always");
  if (is_ca) {
    // digitalSignature too: the permissions CA signs the documents itself (PKCS7_verify checks the
    // signer for the S/MIME signing purpose).
    ok = ok && add_extension(cert.get(), signer_cert, NID_basic_constraints, "critical,CA:TRUE") &&
         add_extension(cert.get(), signer_cert, NID_key_usage,
                       "critical,digitalSignature,keyCertSign,cRLSign");
  } else {
    ok = ok && add_extension(cert.get(), signer_cert, NID_basic_constraints, "critical,CA:FALSE") &&
         add_extension(cert.get(), signer_cert, NID_key_usage, "critical,digitalSignature,keyAgreement");
  }
  ok = ok && X509_sign(cert.get(), self_signed ? key.get() : issuer_key, EVP_sha256()) > 0;
  if (!ok) return openssl_failure("make the certificate of " + common_name);
  return Issued{std::move(cert), std::move(key)};
}

Expected<void> write_issued(const Issued& issued, const std::string& cert_path, const std::string& key_path) {
  if (auto ok = detail::write_file(key_path, detail::key_pem(issued.key.get()), kPrivateMode); !ok) return ok;
  return detail::write_file(cert_path, detail::cert_pem(issued.cert.get()), kPublicMode);
}

Expected<void> write_signed(const std::string& dir, const std::string& xml_path, const std::string& p7s_path,
                            const std::string& document) {
  if (auto ok = detail::write_file(xml_path, document, kPublicMode); !ok) return ok;
  auto signed_document = sign_document(document, dir + "/permissions_ca.pem", permissions_ca_key_path(dir));
  if (!signed_document) return std::move(signed_document).error();
  return detail::write_file(p7s_path, *signed_document, kPublicMode);
}

}  // namespace

std::string identity_subject(const std::string& identity) {
  return fmt::format("CN={},O={}", identity, kOrganization);
}

Expected<void> init_station(const std::string& dir, const Validity& validity) {
  if (auto ok = check_validity(validity); !ok) return ok;
  const Credentials files = credentials_in(dir, "unused");
  struct stat info {};
  if (::stat(files.identity_ca.c_str(), &info) == 0 ||
      ::stat(identity_ca_key_path(dir).c_str(), &info) == 0) {
    return make_error(ErrorCode::kFailedPrecondition,
                      fmt::format("{} already holds a station CA: nothing overwritten (to rotate the CAs, "
                                  "init a new folder and add every identity to it)",
                                  dir));
  }
  if (auto ok = make_folder(dir, 0755); !ok) return ok;
  if (auto ok = make_folder(dir + "/private", 0700); !ok) return ok;
  for (const auto& [name, cert_path, key_path] :
       {std::tuple{"hubrt identity CA", files.identity_ca, identity_ca_key_path(dir)},
        std::tuple{"hubrt permissions CA", files.permissions_ca, permissions_ca_key_path(dir)}}) {
    auto ca = issue(name, validity, true, nullptr, nullptr);
    if (!ca) return std::move(ca).error();
    if (auto ok = write_issued(*ca, cert_path, key_path); !ok) return ok;
  }
  return write_signed(dir, dir + "/governance.xml", files.governance, governance_xml());
}

Expected<void> add_identity(const std::string& dir, const std::string& identity, const Validity& validity,
                            const std::vector<std::string>& publish,
                            const std::vector<std::string>& subscribe,
                            const std::vector<std::uint32_t>& domains) {
  if (auto ok = check_identity_name(identity); !ok) return ok;
  if (auto ok = check_validity(validity); !ok) return ok;
  if (auto ok = check_domains(domains); !ok) return ok;
  const Credentials files = credentials_in(dir, identity);
  auto ca_cert = detail::read_cert(files.identity_ca, "identity CA certificate");
  if (!ca_cert) {
    return make_error(
        ca_cert.error().code,
        ca_cert.error().message + " (make the station's CAs first: hubctl security init " + dir + ")");
  }
  auto ca_key = detail::read_key(identity_ca_key_path(dir), "identity CA key");
  if (!ca_key) return std::move(ca_key).error();
  auto issued = issue(identity, validity, false, ca_cert->get(), ca_key->get());
  if (!issued) return std::move(issued).error();
  if (auto ok = write_issued(*issued, files.identity_cert, files.private_key); !ok) return ok;
  Grant grant;
  grant.name = identity;
  grant.subject = identity_subject(identity);
  grant.not_before_unix = validity.not_before_unix;
  grant.not_after_unix = validity.not_after_unix;
  grant.publish = publish;
  grant.subscribe = subscribe;
  grant.domains = domains;
  return write_signed(dir, fmt::format("{}/{}.permissions.xml", dir, identity), files.permissions,
                      permissions_xml(grant));
}

}  // namespace hubrt::security
