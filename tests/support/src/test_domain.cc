#include "hubrt/test_support/test_domain.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <system_error>
#include <utility>

#include <sys/file.h>

namespace hubrt::test_support {

std::string TestDomain::lock_path_for(std::uint32_t domain_id) {
  std::error_code ec;
  std::filesystem::path dir = std::filesystem::temp_directory_path(ec);
  if (ec) dir = "/tmp";
  return (dir / ("hubrt-test-domain-" + std::to_string(domain_id) + ".lock")).string();
}

Expected<TestDomain> TestDomain::acquire() {
  constexpr std::uint32_t kCount = kLastDomainId - kFirstDomainId + 1;
  const auto start = static_cast<std::uint32_t>(getpid()) % kCount;
  std::string last_open_error;
  for (std::uint32_t i = 0; i < kCount; ++i) {
    const std::uint32_t id = kFirstDomainId + (start + i) % kCount;
    std::string path = lock_path_for(id);
    // Read-only is enough for flock and works on a lock file another user created. CLOEXEC keeps
    // child processes from holding the lock after we are gone.
    // NOLINTNEXTLINE(cppcoreguidelines-pro-type-vararg): open(2) is variadic.
    const int fd = ::open(path.c_str(), O_RDONLY | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) {
      last_open_error = "open " + path + ": " + std::system_category().message(errno);
      continue;
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return TestDomain(fd, id, std::move(path));
    ::close(fd);
  }
  if (!last_open_error.empty()) {
    return make_error(ErrorCode::kIo, "no free test DDS domain id; last failure: " + last_open_error);
  }
  return make_error(ErrorCode::kBusy, "every test DDS domain id from " + std::to_string(kFirstDomainId) +
                                          " to " + std::to_string(kLastDomainId) +
                                          " is locked by another process (" + lock_path_for(kFirstDomainId) +
                                          " ...)");
}

TestDomain::~TestDomain() {
  if (fd_ >= 0) ::close(fd_);  // closing the only descriptor releases the flock
}

TestDomain::TestDomain(TestDomain&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      domain_id_(other.domain_id_),
      lock_path_(std::move(other.lock_path_)) {}

TestDomain& TestDomain::operator=(TestDomain&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
    domain_id_ = other.domain_id_;
    lock_path_ = std::move(other.lock_path_);
  }
  return *this;
}

std::string TestDomain::cyclone_xml() const {
  return dds::loopback_config_xml();
}

dds::DomainConfig TestDomain::config() const {
  return dds::DomainConfig{domain_id_, cyclone_xml()};
}

Environment TestDomain::env() const {
  return {{"CYCLONEDDS_URI", cyclone_xml()}, {dds::kDomainIdEnvVar, std::to_string(domain_id_)}};
}

}  // namespace hubrt::test_support
