// S/MIME signing and verification of the governance and permissions documents.
#include <string>

#include <fmt/format.h>
#include <openssl/pem.h>

#include "hubrt/security/pki.h"

#include "openssl_util.h"

namespace hubrt::security {

using detail::Bio;
using detail::openssl_errors;

Expected<std::string> sign_document(const std::string& document, const std::string& cert_path,
                                    const std::string& key_path) {
  auto cert = detail::read_cert(cert_path, "permissions CA certificate");
  if (!cert) return std::move(cert).error();
  auto key = detail::read_key(key_path, "permissions CA key");
  if (!key) return std::move(key).error();
  // The flags of OpenSSL's demos/smime/smsign.c plus PKCS7_TEXT (`openssl smime -sign -text`):
  // the signed content carries a "Content-Type: text/plain" header, which Cyclone's
  // PKCS7_verify(..., PKCS7_TEXT) strips again.
  constexpr int kFlags = PKCS7_DETACHED | PKCS7_STREAM | PKCS7_TEXT;
  Bio in(BIO_new_mem_buf(document.data(), static_cast<int>(document.size())));
  detail::Pkcs7 p7(PKCS7_sign(cert->get(), key->get(), nullptr, in.get(), kFlags));
  Bio out(BIO_new(BIO_s_mem()));
  if (!p7 || SMIME_write_PKCS7(out.get(), p7.get(), in.get(), kFlags) != 1) {
    return make_error(ErrorCode::kInternal, "cannot sign a document: " + openssl_errors());
  }
  char* data = nullptr;
  const long size = BIO_get_mem_data(out.get(), &data);
  return std::string(data, static_cast<std::size_t>(size));
}

Expected<std::string> verify_document(const std::string& path, const std::string& what,
                                      const std::string& ca_path, std::int64_t now_unix) {
  auto ca = detail::read_cert(ca_path, "permissions CA certificate");
  if (!ca) return std::move(ca).error();
  auto text = detail::read_small_file(path, what);
  if (!text) return std::move(text).error();
  Bio in(BIO_new_mem_buf(text->data(), static_cast<int>(text->size())));
  BIO* content = nullptr;
  detail::Pkcs7 p7(SMIME_read_PKCS7(in.get(), &content));
  Bio content_owner(content);
  if (!p7) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{} {}: not an S/MIME signed document ({})", what, path, openssl_errors()));
  }
  detail::Store store(X509_STORE_new());
  X509_STORE_add_cert(store.get(), ca->get());
  X509_VERIFY_PARAM_set_time(X509_STORE_get0_param(store.get()), static_cast<time_t>(now_unix));
  Bio out(BIO_new(BIO_s_mem()));
  if (PKCS7_verify(p7.get(), nullptr, store.get(), content, out.get(), PKCS7_TEXT) != 1) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{} {} is not signed by the permissions CA {} ({})", what, path, ca_path,
                                  openssl_errors()));
  }
  char* data = nullptr;
  const long size = BIO_get_mem_data(out.get(), &data);
  // S/MIME signs the canonical text form, CRLF line ends; give the document back as it was made.
  std::string document(data, static_cast<std::size_t>(size));
  std::erase(document, '\r');
  return document;
}

}  // namespace hubrt::security
