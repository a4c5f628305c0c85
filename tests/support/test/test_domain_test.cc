#include "hubrt/test_support/test_domain.h"

#include <chrono>
#include <string>

#include <gtest/gtest.h>

#include "hubrt/test_support/child_process.h"

namespace hubrt::test_support {
namespace {

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

}  // namespace
}  // namespace hubrt::test_support
