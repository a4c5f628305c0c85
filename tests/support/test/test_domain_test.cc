#include "hubrt/test_support/test_domain.h"

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/test_support/child_process.h"

namespace hubrt::test_support {
namespace {

using dds::disjoint;
using dds::domain_port_band;
using dds::ephemeral_port_range;
using dds::PortRange;
using std::chrono::seconds;

std::string value_of(const Environment& env, const std::string& name) {
  for (const auto& [key, value] : env) {
    if (key == name) return value;
  }
  return "<unset>";
}

TEST(TestDomain, TwoDomainsInOneProcessGetDifferentIds) {
  auto a = TestDomain::acquire();
  ASSERT_TRUE(a) << a.error().message;
  auto b = TestDomain::acquire();
  ASSERT_TRUE(b) << b.error().message;
  EXPECT_NE(a->domain_id(), b->domain_id());
  for (const auto* d : {&*a, &*b}) {
    EXPECT_GE(d->domain_id(), TestDomain::kFirstDomainId);
    EXPECT_LE(d->domain_id(), TestDomain::kLastDomainId);
  }
}

// A test with a Fast DDS participant: no socket bound to port 0 can sit on its domain's ports.
TEST(TestDomain, AcquireOutsideEphemeralPortsGivesAnIdNoEphemeralSocketCanTakeAPortOf) {
  const PortRange ephemeral = ephemeral_port_range();
  EXPECT_LE(ephemeral.first, ephemeral.last);
  std::vector<TestDomain> held;
  for (int i = 0; i < 3; ++i) {  // 3: ids 100 and 215-230 on Linux's default range
    auto domain = TestDomain::acquire_outside_ephemeral_ports();
    ASSERT_TRUE(domain) << domain.error().message;
    const PortRange band = domain_port_band(domain->domain_id());
    EXPECT_TRUE(disjoint(band, ephemeral))
        << "domain " << domain->domain_id() << ": ports " << band.first << "-" << band.last
        << " meet the ephemeral range " << ephemeral.first << "-" << ephemeral.last;
    held.push_back(std::move(*domain));
  }
}

// The ids outside the ephemeral range are kept for the tests that need them: 114 others come first.
TEST(TestDomain, AcquireTakesAnIdInsideTheEphemeralRangeWhileOneIsFree) {
  const PortRange ephemeral = ephemeral_port_range();
  if (disjoint(PortRange{domain_port_band(TestDomain::kFirstDomainId).first,
                         domain_port_band(TestDomain::kLastDomainId).last},
               ephemeral)) {
    GTEST_SKIP() << "this machine's ephemeral range " << ephemeral.first << "-" << ephemeral.last
                 << " meets no test domain's ports";
  }
  auto domain = TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  EXPECT_FALSE(disjoint(domain_port_band(domain->domain_id()), ephemeral)) << domain->domain_id();
}

TEST(TestDomain, IdIsLockedAgainstOtherProcessesAndFreedOnDestruction) {
  std::string path;
  {
    auto domain = TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    path = domain->lock_path();
    EXPECT_EQ(path, TestDomain::lock_path_for(domain->domain_id()));
    // flock(1) -n exits 1 when the lock is held elsewhere.
    auto probe = ChildProcess::start("flock", {"-n", path, "true"});
    ASSERT_TRUE(probe) << probe.error().message;
    auto status = probe->wait(seconds(10));  // generous: only process start-up on a busy machine
    ASSERT_TRUE(status) << status.error().message;
    EXPECT_TRUE(status->exited_with(1)) << status->describe();
  }
  auto probe = ChildProcess::start("flock", {"-n", path, "true"});
  ASSERT_TRUE(probe) << probe.error().message;
  auto status = probe->wait(seconds(10));
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe();
}

TEST(TestDomain, MovedDomainKeepsTheLock) {
  auto domain = TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  TestDomain moved = std::move(*domain);
  auto probe = ChildProcess::start("flock", {"-n", moved.lock_path(), "true"});
  ASSERT_TRUE(probe) << probe.error().message;
  auto status = probe->wait(seconds(10));
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(1)) << status->describe();
}

TEST(TestDomain, ConfigAndEnvCarryTheIdAndTheLoopbackConfiguration) {
  auto domain = TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  const dds::DomainConfig config = domain->config();
  EXPECT_EQ(config.domain_id, domain->domain_id());
  EXPECT_EQ(config.cyclone_xml, dds::loopback_config_xml());
  EXPECT_NE(config.cyclone_xml.find("<NetworkInterface name=\"lo\"/>"), std::string::npos);
  const Environment env = domain->env();
  EXPECT_EQ(value_of(env, "ROS_DOMAIN_ID"), std::to_string(domain->domain_id()));
  EXPECT_EQ(value_of(env, "CYCLONEDDS_URI"), dds::loopback_config_xml());
}

// flock(1) -n on `path`: exit status 1 when another process holds the lock, 0 when it is free.
int probe_lock(const std::string& path) {
  auto probe = ChildProcess::start("flock", {"-n", path, "true"});
  EXPECT_TRUE(probe) << probe.error().message;
  if (!probe) return -1;
  auto status = probe->wait(seconds(10));  // generous: only process start-up on a busy machine
  EXPECT_TRUE(status) << status.error().message;
  if (!status) return -1;
  return status->exited_with(0) ? 0 : (status->exited_with(1) ? 1 : -1);
}

// A benchmark probing a plant's domain (bench/plant.py) takes that id itself: once, while held.
TEST(TestDomain, TakeHoldsTheNamedIdOnceAndRefusesAnIdAboveTheLast) {
  auto acquired = TestDomain::acquire();  // a free id now, so that taking it cannot meet another test's
  ASSERT_TRUE(acquired) << acquired.error().message;
  const std::uint32_t id = acquired->domain_id();
  std::optional<TestDomain> held(std::move(*acquired));
  auto again = TestDomain::take(id);
  ASSERT_FALSE(again);
  EXPECT_EQ(again.error().code, ErrorCode::kBusy);
  held.reset();  // the lock goes
  auto taken = TestDomain::take(id);
  ASSERT_TRUE(taken) << taken.error().message;
  EXPECT_EQ(taken->domain_id(), id);
  auto above = TestDomain::take(dds::kMaxDomainId + 1);
  ASSERT_FALSE(above);
  EXPECT_EQ(above.error().code, ErrorCode::kInvalidArgument);
}

TEST(TestDomainRange, HoldsConsecutiveIdsEachLockedUntilItGoes) {
  std::vector<std::string> paths;
  {
    auto range = TestDomainRange::acquire(3);
    ASSERT_TRUE(range) << range.error().message;
    ASSERT_EQ(range->size(), 3U);
    EXPECT_EQ(range->last_id(), range->first_id() + 2);
    EXPECT_EQ(range->text(), std::to_string(range->first_id()) + "-" + std::to_string(range->first_id() + 2));
    EXPECT_GE(range->first_id(), TestDomain::kFirstDomainId);
    EXPECT_LE(range->last_id(), TestDomain::kLastDomainId);
    for (std::size_t i = 0; i < range->size(); ++i) {
      EXPECT_EQ(range->at(i).domain_id(), range->first_id() + i);
      paths.push_back(range->at(i).lock_path());
      EXPECT_EQ(probe_lock(paths.back()), 1) << paths.back() << " is not held";
    }
  }
  for (const auto& path : paths) EXPECT_EQ(probe_lock(path), 0) << path << " still held";
}

TEST(TestDomainRange, NeverOverlapsAnIdHeldInThisProcessOrElsewhere) {
  auto single = TestDomain::acquire();
  ASSERT_TRUE(single) << single.error().message;
  auto a = TestDomainRange::acquire(4);
  ASSERT_TRUE(a) << a.error().message;
  auto b = TestDomainRange::acquire(4);
  ASSERT_TRUE(b) << b.error().message;
  // flock is per open file description: a second lock on a held id fails in this process too.
  const auto inside = [](const TestDomainRange& r, std::uint32_t id) {
    return id >= r.first_id() && id <= r.last_id();
  };
  EXPECT_FALSE(inside(*a, single->domain_id()));
  EXPECT_FALSE(inside(*b, single->domain_id()));
  EXPECT_TRUE(b->last_id() < a->first_id() || b->first_id() > a->last_id())
      << a->text() << " and " << b->text();
}

TEST(TestDomainRange, RefusesAnEmptyOrOversizedRun) {
  EXPECT_EQ(TestDomainRange::acquire(0).error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(TestDomainRange::acquire(TestDomainRange::kMaxCount + 1).error().code,
            ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace hubrt::test_support
