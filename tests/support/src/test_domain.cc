#include "hubrt/test_support/test_domain.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <system_error>
#include <utility>

#include <sys/file.h>

namespace hubrt::test_support {

using dds::disjoint;
using dds::domain_port_band;
using dds::ephemeral_port_range;
using dds::PortRange;

namespace {

constexpr std::uint32_t kIdCount = TestDomain::kLastDomainId - TestDomain::kFirstDomainId + 1;

// Which ids a pass of acquire() may take.
enum class Ports { kInsideEphemeralRange, kOutsideEphemeralRange };

bool ports_match(std::uint32_t domain_id, Ports ports, PortRange ephemeral) {
  return disjoint(domain_port_band(domain_id), ephemeral) == (ports == Ports::kOutsideEphemeralRange);
}

}  // namespace

std::string TestDomain::lock_path_for(std::uint32_t domain_id) {
  std::error_code ec;
  std::filesystem::path dir = std::filesystem::temp_directory_path(ec);
  if (ec) dir = "/tmp";
  return (dir / ("hubrt-test-domain-" + std::to_string(domain_id) + ".lock")).string();
}

Expected<TestDomain> TestDomain::try_lock(std::uint32_t domain_id) {
  std::string path = lock_path_for(domain_id);
  // Read-only is enough for flock and works on a lock file another user created. CLOEXEC keeps
  // child processes from holding the lock after we are gone.
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-vararg): open(2) is variadic.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0)
    return make_error(ErrorCode::kIo, "open " + path + ": " + std::system_category().message(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return TestDomain(fd, domain_id, std::move(path));
  ::close(fd);
  return make_error(ErrorCode::kBusy, path + " is locked by another process");
}

Expected<TestDomain> TestDomain::take(std::uint32_t domain_id) {
  if (domain_id > dds::kMaxDomainId) {
    return make_error(ErrorCode::kInvalidArgument, "DDS domain id " + std::to_string(domain_id) +
                                                       " is above " + std::to_string(dds::kMaxDomainId));
  }
  return try_lock(domain_id);
}

namespace {

// The first free id among those `ports` admits, in an order that starts at a point derived from
// the process id. Returns kBusy when none is free, kIo when a lock file could not be opened.
// `try_lock` is TestDomain::try_lock, private, handed in by its members.
Expected<TestDomain> first_free(Ports ports, PortRange ephemeral,
                                Expected<TestDomain> (*try_lock)(std::uint32_t)) {
  const auto start = static_cast<std::uint32_t>(getpid()) % kIdCount;
  std::string last_open_error;
  for (std::uint32_t i = 0; i < kIdCount; ++i) {
    const std::uint32_t id = TestDomain::kFirstDomainId + (start + i) % kIdCount;
    if (!ports_match(id, ports, ephemeral)) continue;
    auto domain = try_lock(id);
    if (domain) return domain;
    if (domain.error().code == ErrorCode::kIo) last_open_error = domain.error().message;
  }
  if (!last_open_error.empty()) {
    return make_error(ErrorCode::kIo, "no free test DDS domain id; last failure: " + last_open_error);
  }
  return make_error(ErrorCode::kBusy, "");
}

}  // namespace

Expected<TestDomain> TestDomain::acquire() {
  const PortRange ephemeral = ephemeral_port_range();
  // The ids outside the ephemeral range last: the tests that need them find them free.
  auto domain = first_free(Ports::kInsideEphemeralRange, ephemeral, &try_lock);
  if (domain || domain.error().code != ErrorCode::kBusy) return domain;
  domain = first_free(Ports::kOutsideEphemeralRange, ephemeral, &try_lock);
  if (domain || domain.error().code != ErrorCode::kBusy) return domain;
  return make_error(ErrorCode::kBusy, "every test DDS domain id from " + std::to_string(kFirstDomainId) +
                                          " to " + std::to_string(kLastDomainId) +
                                          " is locked by another process (" + lock_path_for(kFirstDomainId) +
                                          " ...)");
}

Expected<TestDomain> TestDomain::acquire_outside_ephemeral_ports() {
  const PortRange ephemeral = ephemeral_port_range();
  const std::string range = std::to_string(ephemeral.first) + "-" + std::to_string(ephemeral.last);
  bool any = false;
  for (std::uint32_t id = kFirstDomainId; id <= kLastDomainId; ++id) {
    any = any || ports_match(id, Ports::kOutsideEphemeralRange, ephemeral);
  }
  if (!any) {
    return make_error(ErrorCode::kUnavailable,
                      "no test DDS domain id from " + std::to_string(kFirstDomainId) + " to " +
                          std::to_string(kLastDomainId) +
                          " has its ports (7400 + 250 * id ... + 249) outside this machine's ephemeral "
                          "port range " +
                          range + " (net.ipv4.ip_local_port_range); Linux's default is 32768-60999");
  }
  auto domain = first_free(Ports::kOutsideEphemeralRange, ephemeral, &try_lock);
  if (domain || domain.error().code != ErrorCode::kBusy) return domain;
  return make_error(ErrorCode::kBusy,
                    "every test DDS domain id whose ports lie outside the ephemeral port range " + range +
                        " is locked by another process");
}

Expected<TestDomainRange> TestDomainRange::acquire(std::uint32_t count) {
  if (count == 0 || count > kMaxCount) {
    return make_error(
        ErrorCode::kInvalidArgument,
        "a test domain range holds 1 to " + std::to_string(kMaxCount) + " ids, not " + std::to_string(count));
  }
  constexpr std::uint32_t kStarts = TestDomain::kLastDomainId - TestDomain::kFirstDomainId + 1;
  const auto offset = static_cast<std::uint32_t>(getpid()) % kStarts;
  std::string last_open_error;
  for (std::uint32_t i = 0; i < kStarts; ++i) {
    const std::uint32_t first = TestDomain::kFirstDomainId + (offset + i) % kStarts;
    if (first + count - 1 > TestDomain::kLastDomainId) continue;  // a run does not wrap around
    std::vector<TestDomain> run;
    for (std::uint32_t id = first; id < first + count; ++id) {
      auto domain = TestDomain::try_lock(id);
      if (!domain) {
        if (domain.error().code == ErrorCode::kIo) last_open_error = domain.error().message;
        break;  // `run` goes out of scope: its locks are released
      }
      run.push_back(std::move(*domain));
    }
    if (run.size() == count) return TestDomainRange(std::move(run));
  }
  if (!last_open_error.empty()) {
    return make_error(ErrorCode::kIo, "no free run of test DDS domain ids; last failure: " + last_open_error);
  }
  return make_error(ErrorCode::kBusy, "no " + std::to_string(count) +
                                          " consecutive test DDS domain ids from " +
                                          std::to_string(TestDomain::kFirstDomainId) + " to " +
                                          std::to_string(TestDomain::kLastDomainId) + " are free");
}

std::string TestDomainRange::text() const {
  return std::to_string(first_id()) + "-" + std::to_string(last_id());
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
