#include "openssl_util.h"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <openssl/err.h>
#include <openssl/pem.h>
#include <sys/stat.h>

namespace hubrt::security::detail {
namespace {

constexpr std::size_t kMaxFileBytes = 1024 * 1024;  // certificates and documents are a few KiB

std::string bio_text(BIO* bio) {
  char* data = nullptr;
  const long size = BIO_get_mem_data(bio, &data);
  return size > 0 ? std::string(data, static_cast<std::size_t>(size)) : std::string();
}

}  // namespace

std::string openssl_errors() {
  std::string text;
  while (const unsigned long code = ERR_get_error()) {
    std::array<char, 256> buffer{};
    ERR_error_string_n(code, buffer.data(), buffer.size());
    if (!text.empty()) text += "; ";
    text += buffer.data();
  }
  return text.empty() ? "no detail from OpenSSL" : text;
}

Expected<std::string> read_small_file(const std::string& path, const std::string& what) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    const int error = errno;
    return make_error(error == ENOENT   ? ErrorCode::kNotFound
                      : error == EACCES ? ErrorCode::kPermissionDenied
                                        : ErrorCode::kIo,
                      fmt::format("{} {}: {}", what, path, std::strerror(error)));
  }
  if (!S_ISREG(info.st_mode))
    return make_error(ErrorCode::kIo, fmt::format("{} {}: not a regular file", what, path));
  if (static_cast<std::size_t>(info.st_size) > kMaxFileBytes) {
    return make_error(ErrorCode::kOutOfRange,
                      fmt::format("{} {}: {} bytes, more than the {} a certificate or document may have",
                                  what, path, info.st_size, kMaxFileBytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return make_error(errno == EACCES ? ErrorCode::kPermissionDenied : ErrorCode::kIo,
                      fmt::format("{} {}: cannot be read ({})", what, path, std::strerror(errno)));
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Expected<Cert> read_cert(const std::string& path, const std::string& what) {
  auto text = read_small_file(path, what);
  if (!text) return std::move(text).error();
  Bio bio(BIO_new_mem_buf(text->data(), static_cast<int>(text->size())));
  Cert cert(PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr));
  if (!cert) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{} {}: not a PEM certificate ({})", what, path, openssl_errors()));
  }
  return cert;
}

Expected<Key> read_key(const std::string& path, const std::string& what) {
  auto text = read_small_file(path, what);
  if (!text) return std::move(text).error();
  Bio bio(BIO_new_mem_buf(text->data(), static_cast<int>(text->size())));
  Key key(PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, nullptr));
  if (!key) {
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("{} {}: not an unencrypted PEM private key ({})", what, path, openssl_errors()));
  }
  return key;
}

Expected<void> write_file(const std::string& path, const std::string& text, unsigned mode) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, mode);
  if (fd < 0)
    return make_error(ErrorCode::kIo, fmt::format("cannot write {}: {}", path, std::strerror(errno)));
  // open() applies the umask and leaves an existing file's mode: set it explicitly.
  bool ok = ::fchmod(fd, mode) == 0;
  std::size_t done = 0;
  while (ok && done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    ok = n > 0;
    if (ok) done += static_cast<std::size_t>(n);
  }
  const int error = errno;
  ok = (::close(fd) == 0) && ok;
  if (!ok) return make_error(ErrorCode::kIo, fmt::format("cannot write {}: {}", path, std::strerror(error)));
  return {};
}

std::string cert_pem(X509* cert) {
  Bio bio(BIO_new(BIO_s_mem()));
  PEM_write_bio_X509(bio.get(), cert);
  return bio_text(bio.get());
}

std::string key_pem(EVP_PKEY* key) {
  Bio bio(BIO_new(BIO_s_mem()));
  PEM_write_bio_PrivateKey(bio.get(), key, nullptr, nullptr, 0, nullptr, nullptr);
  return bio_text(bio.get());
}

std::string asn1_time_text(const ASN1_TIME* time) {
  std::tm tm{};
  if (ASN1_TIME_to_tm(time, &tm) != 1) return "(unreadable time)";
  return fmt::format("{:04}-{:02}-{:02} {:02}:{:02}:{:02} UTC", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                     tm.tm_hour, tm.tm_min, tm.tm_sec);
}

std::string iso8601_utc(std::int64_t unix_seconds) {
  const auto seconds = static_cast<std::time_t>(unix_seconds);
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                     tm.tm_hour, tm.tm_min, tm.tm_sec);
}

std::string subject_text(X509* cert) {
  Bio bio(BIO_new(BIO_s_mem()));
  X509_NAME_print_ex(bio.get(), X509_get_subject_name(cert), 0, XN_FLAG_RFC2253);
  return bio_text(bio.get());
}

}  // namespace hubrt::security::detail
