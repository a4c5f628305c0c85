// Checking a participant's credentials before Cyclone does, with messages that name the file and
// the cause (Cyclone's own refusal reads "Certificate expired" on its log, without the file).
#include <fmt/format.h>
#include <openssl/x509_vfy.h>

#include "hubrt/security/participant_security.h"
#include "hubrt/security/pki.h"

#include "openssl_util.h"

namespace hubrt::security {
namespace {

using detail::Cert;

Expected<void> check_dates(X509* cert, const std::string& what, const std::string& path,
                           std::int64_t now_unix) {
  auto now = static_cast<time_t>(now_unix);
  if (X509_cmp_time(X509_get0_notBefore(cert), &now) > 0) {
    return make_error(ErrorCode::kFailedPrecondition,
                      fmt::format("{} {} is not valid yet: valid from {}", what, path,
                                  detail::asn1_time_text(X509_get0_notBefore(cert))));
  }
  if (X509_cmp_time(X509_get0_notAfter(cert), &now) < 0) {
    return make_error(ErrorCode::kFailedPrecondition,
                      fmt::format("{} {} has expired: valid until {}; issue a new one (hubctl security add)",
                                  what, path, detail::asn1_time_text(X509_get0_notAfter(cert))));
  }
  return {};
}

Expected<void> check_issued_by(X509* cert, X509* ca, const Credentials& files, std::int64_t now_unix) {
  detail::Store store(X509_STORE_new());
  detail::StoreCtx ctx(X509_STORE_CTX_new());
  X509_STORE_add_cert(store.get(), ca);
  if (!store || !ctx || X509_STORE_CTX_init(ctx.get(), store.get(), cert, nullptr) != 1) {
    return make_error(ErrorCode::kInternal, "cannot check a certificate: " + detail::openssl_errors());
  }
  X509_STORE_CTX_set_time(ctx.get(), 0, static_cast<time_t>(now_unix));
  if (X509_verify_cert(ctx.get()) == 1) return {};
  const int error = X509_STORE_CTX_get_error(ctx.get());
  (void)detail::openssl_errors();  // the store context's reason is the one to report
  return make_error(
      ErrorCode::kFailedPrecondition,
      fmt::format("identity certificate {} ({}) is not trusted by the station's identity CA {} ({}): "
                  "{}",
                  files.identity_cert, detail::subject_text(cert), files.identity_ca,
                  detail::subject_text(ca), X509_verify_cert_error_string(error)));
}

}  // namespace

Expected<void> check_credentials(const Credentials& files, std::int64_t now_unix) {
  auto identity_ca = detail::read_cert(files.identity_ca, "identity CA certificate");
  if (!identity_ca) return std::move(identity_ca).error();
  auto permissions_ca = detail::read_cert(files.permissions_ca, "permissions CA certificate");
  if (!permissions_ca) return std::move(permissions_ca).error();
  auto cert = detail::read_cert(files.identity_cert, "identity certificate");
  if (!cert) return std::move(cert).error();
  auto key = detail::read_key(files.private_key, "private key");
  if (!key) return std::move(key).error();

  if (auto ok = check_dates(identity_ca->get(), "identity CA certificate", files.identity_ca, now_unix); !ok)
    return ok;
  if (auto ok =
          check_dates(permissions_ca->get(), "permissions CA certificate", files.permissions_ca, now_unix);
      !ok) {
    return ok;
  }
  if (auto ok = check_dates(cert->get(), "identity certificate", files.identity_cert, now_unix); !ok)
    return ok;
  if (auto ok = check_issued_by(cert->get(), identity_ca->get(), files, now_unix); !ok) return ok;
  if (X509_check_private_key(cert->get(), key->get()) != 1) {
    (void)detail::openssl_errors();
    return make_error(ErrorCode::kFailedPrecondition,
                      fmt::format("private key {} does not belong to the identity certificate {}",
                                  files.private_key, files.identity_cert));
  }
  for (const auto& [path, what] : {std::pair{files.governance, "governance document"},
                                   std::pair{files.permissions, "permissions document"}}) {
    auto content = verify_document(path, what, files.permissions_ca, now_unix);
    if (!content) {
      Error error = std::move(content).error();
      if (error.code == ErrorCode::kInvalidArgument) error.code = ErrorCode::kFailedPrecondition;
      return error;
    }
  }
  return {};
}

std::string describe_identity(const Credentials& files) {
  auto cert = detail::read_cert(files.identity_cert, "identity certificate");
  auto ca = detail::read_cert(files.identity_ca, "identity CA certificate");
  (void)detail::openssl_errors();
  const std::string identity =
      cert ? fmt::format("certificate {} ({}, valid until {})", detail::subject_text(cert->get()),
                         files.identity_cert, detail::asn1_time_text(X509_get0_notAfter(cert->get())))
           : fmt::format("certificate {} (unreadable)", files.identity_cert);
  const std::string authority =
      ca ? fmt::format("identity CA {} ({})", detail::subject_text(ca->get()), files.identity_ca)
         : fmt::format("identity CA {} (unreadable)", files.identity_ca);
  return identity + " of " + authority;
}

}  // namespace hubrt::security
