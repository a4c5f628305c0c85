// OpenSSL objects owned by unique_ptr, reading and writing PEM files, and OpenSSL's error queue as
// text. Private to hubrt_security.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <openssl/bio.h>
#include <openssl/evp.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>

#include "hubrt/base/status.h"

namespace hubrt::security::detail {

struct BioFree {
  void operator()(BIO* bio) const noexcept { BIO_free_all(bio); }
};
struct KeyFree {
  void operator()(EVP_PKEY* key) const noexcept { EVP_PKEY_free(key); }
};
struct CertFree {
  void operator()(X509* cert) const noexcept { X509_free(cert); }
};
struct StoreFree {
  void operator()(X509_STORE* store) const noexcept { X509_STORE_free(store); }
};
struct StoreCtxFree {
  void operator()(X509_STORE_CTX* ctx) const noexcept { X509_STORE_CTX_free(ctx); }
};
struct Pkcs7Free {
  void operator()(PKCS7* p7) const noexcept { PKCS7_free(p7); }
};
using Bio = std::unique_ptr<BIO, BioFree>;
using Key = std::unique_ptr<EVP_PKEY, KeyFree>;
using Cert = std::unique_ptr<X509, CertFree>;
using Store = std::unique_ptr<X509_STORE, StoreFree>;
using StoreCtx = std::unique_ptr<X509_STORE_CTX, StoreCtxFree>;
using Pkcs7 = std::unique_ptr<PKCS7, Pkcs7Free>;

// The entries of OpenSSL's (thread-local) error queue, emptied, as "; "-separated text; "no
// detail from OpenSSL" when it is empty.
std::string openssl_errors();

// A whole file, at most `max_bytes`. Errors: kNotFound / kPermissionDenied / kIo naming `what`
// and the path; kOutOfRange when larger.
Expected<std::string> read_small_file(const std::string& path, const std::string& what);

Expected<Cert> read_cert(const std::string& path, const std::string& what);
Expected<Key> read_key(const std::string& path, const std::string& what);

// Writes `text` to `path` (replacing it) with `mode` set whatever the umask.
Expected<void> write_file(const std::string& path, const std::string& text, unsigned mode);

std::string cert_pem(X509* cert);
std::string key_pem(EVP_PKEY* key);

// "2026-11-24 14:50:00 UTC" for a certificate time.
std::string asn1_time_text(const ASN1_TIME* time);
// "2026-11-24T14:50:00" (UTC), the form the permissions document's validity takes.
std::string iso8601_utc(std::int64_t unix_seconds);
// The certificate's subject, one line, e.g. "CN=dock_ecu,O=hubrt station".
std::string subject_text(X509* cert);

}  // namespace hubrt::security::detail
