// A DDS domain id of its own for each test process, so that tests running in parallel (and other
// DDS programs on the machine) never see each other's traffic.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/dds/domain.h"

namespace hubrt::test_support {

// Environment variables for a child process: name and value.
using Environment = std::vector<std::pair<std::string, std::string>>;

// Holds an exclusive flock(2) on "<tmp>/hubrt-test-domain-<id>.lock" (tmp from TMPDIR, else
// /tmp) for one id in [kFirstDomainId, kLastDomainId] for as long as it lives; every process that
// uses TestDomain therefore gets a different id. The lock goes away with the process, so a
// crashed test never leaves an id taken. Move-only.
// Thread-safety: acquire() is thread-safe; the accessors are const.
class TestDomain {
 public:
  static constexpr std::uint32_t kFirstDomainId = 100;
  static constexpr std::uint32_t kLastDomainId = 230;

  // Takes the first free id, starting at a point derived from the process id so that parallel
  // tests rarely contend. Errors: kBusy if every id is taken; kIo if no lock file can be opened.
  static Expected<TestDomain> acquire();

  ~TestDomain();
  TestDomain(const TestDomain&) = delete;
  TestDomain& operator=(const TestDomain&) = delete;
  TestDomain(TestDomain&& other) noexcept;
  TestDomain& operator=(TestDomain&& other) noexcept;

  [[nodiscard]] std::uint32_t domain_id() const noexcept { return domain_id_; }
  // The loopback-only Cyclone configuration (dds::loopback_config_xml()).
  [[nodiscard]] std::string cyclone_xml() const;
  // domain_id() and cyclone_xml() together, for dds::Participant::create().
  [[nodiscard]] dds::DomainConfig config() const;
  // What a child process (hubd, hubctl) needs to join the same domain with the same
  // configuration: CYCLONEDDS_URI=<loopback xml> and ROS_DOMAIN_ID=<id>; the child reads them
  // with dds::domain_config_from_environment().
  [[nodiscard]] Environment env() const;
  // The lock file held, for diagnostics.
  [[nodiscard]] const std::string& lock_path() const noexcept { return lock_path_; }

  // The lock file for `domain_id`, whether held or not.
  static std::string lock_path_for(std::uint32_t domain_id);

 private:
  TestDomain(int fd, std::uint32_t domain_id, std::string lock_path) noexcept
      : fd_(fd), domain_id_(domain_id), lock_path_(std::move(lock_path)) {}

  int fd_ = -1;
  std::uint32_t domain_id_ = 0;
  std::string lock_path_;
};

}  // namespace hubrt::test_support
