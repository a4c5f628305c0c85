// A DDS domain id of its own for each test process, so that tests running in parallel (and other
// DDS programs on the machine) never see each other's traffic.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/dds/domain.h"
#include "hubrt/dds/ports.h"

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
  // tests rarely contend, and the ids of acquire_outside_ephemeral_ports() only when no other is
  // free. Errors: kBusy if every id is taken; kIo if no lock file can be opened.
  static Expected<TestDomain> acquire();
  // An id none of whose ports (dds::domain_port_band) the kernel can give a socket bound to port 0
  // (dds::ephemeral_port_range): 100 and 215-230 on Linux's default range. A test whose participants
  // do not announce their domain id needs one. Fast DDS 2.9 sends no PID_DOMAIN_ID in its
  // participant announcements, and Cyclone 0.10 takes an announcement without one as of its own
  // domain. Cyclone also reads its transmit socket, bound to port 0. A Fast DDS planner's
  // announcements to its domain's discovery ports would reach a Cyclone hub of another test whose
  // transmit socket sits on one of them: the two match across domains. CI saw a Fast DDS planner
  // receive another test's Dock ECU States (docs/ci.md). Errors: kUnavailable when the ephemeral
  // range covers every id's ports; kBusy when every such id is taken; kIo as acquire().
  static Expected<TestDomain> acquire_outside_ephemeral_ports();
  // Takes `domain_id` itself, any id up to dds::kMaxDomainId, without waiting: a benchmark that
  // probes a domain other programs already run in (bench/plant.py). Errors: kInvalidArgument above
  // dds::kMaxDomainId; kBusy when another process holds it; kIo when its lock file cannot be opened.
  static Expected<TestDomain> take(std::uint32_t domain_id);

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
  friend class TestDomainRange;
  // Locks `domain_id`'s file without waiting. Errors: kBusy when another process holds it; kIo
  // when the file cannot be opened.
  static Expected<TestDomain> try_lock(std::uint32_t domain_id);
  TestDomain(int fd, std::uint32_t domain_id, std::string lock_path) noexcept
      : fd_(fd), domain_id_(domain_id), lock_path_(std::move(lock_path)) {}

  int fd_ = -1;
  std::uint32_t domain_id_ = 0;
  std::string lock_path_;
};

// A run of consecutive DDS domain ids for one test process — a plant of stations, one domain each
// (`hubctl watch --domain 10-12`) — taken with TestDomain's file locks, one lock per id, held for
// as long as it lives. Move-only.
// Thread-safety: acquire() is thread-safe; the accessors are const.
class TestDomainRange {
 public:
  // At most this many ids at once: a range takes ids other tests could use.
  static constexpr std::uint32_t kMaxCount = 8;

  // `count` consecutive free ids in [TestDomain::kFirstDomainId, TestDomain::kLastDomainId],
  // starting at a point derived from the process id; every id's lock is taken without waiting, and
  // a start whose run holds an id locked elsewhere is given up (its locks released) for the next.
  // Errors: kInvalidArgument for a count of 0 or above kMaxCount; kBusy if no run of `count` free
  // ids exists; kIo if no lock file can be opened.
  static Expected<TestDomainRange> acquire(std::uint32_t count);

  [[nodiscard]] std::uint32_t first_id() const noexcept { return domains_.front().domain_id(); }
  [[nodiscard]] std::uint32_t last_id() const noexcept { return domains_.back().domain_id(); }
  [[nodiscard]] std::size_t size() const noexcept { return domains_.size(); }
  // The i-th domain of the run (its id is first_id() + i). Precondition: i < size().
  [[nodiscard]] const TestDomain& at(std::size_t i) const { return domains_.at(i); }
  // "first-last", as `hubctl --domain` takes it.
  [[nodiscard]] std::string text() const;

 private:
  explicit TestDomainRange(std::vector<TestDomain> domains) noexcept : domains_(std::move(domains)) {}
  std::vector<TestDomain> domains_;  // consecutive ids, ascending; never empty
};

}  // namespace hubrt::test_support
