// TestDomain::env() must carry the domain id and the loopback configuration into a child process:
// a probe started with it must reach a reader in this process's private domain.
#include <signal.h>

#include <array>
#include <chrono>
#include <optional>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/discovery.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/read_condition.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/waitset.h"
#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/test_domain.h"

#include "probe_listener.h"
#include "test_types_traits.h"

namespace hubrt::test_support {
namespace {

using dds::test::Counter;
using std::chrono::seconds;

// Generous: the probe's start-up and discovery on a busy 2-core machine, possibly under a
// sanitizer; the test waits on events and only gives up at this bound.
constexpr Duration kBound = seconds(30);

TEST(TestDomainEnv, ChildProcessJoinsTheSameDomainOverLoopback) {
  auto domain = TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  ProbeListener listener;
  ASSERT_NO_FATAL_FAILURE(open_probe_listener(*domain, "env_probe_test", listener));

  auto probe = ChildProcess::start(HUBRT_DDS_ENV_PROBE, {}, domain->env());
  ASSERT_TRUE(probe) << probe.error().message;
  ASSERT_TRUE(probe->wait_for_output("probe: joined domain " + std::to_string(domain->domain_id()), kBound))
      << probe->stdout_text() << probe->stderr_text();

  std::array<dds::WaitSet::Token, 2> fired{};
  auto n = listener.waitset->wait(fired, kBound);
  ASSERT_TRUE(n.is_ok());
  ASSERT_EQ(n.value(), 1u) << "no sample from the probe; its output:\n"
                           << probe->stdout_text() << probe->stderr_text();
  EXPECT_EQ(fired[0], 1);
  Counter sample{};
  auto taken = listener.reader->take_next(sample);
  ASSERT_TRUE(taken.is_ok());
  ASSERT_TRUE(taken.value());
  EXPECT_EQ(sample.count, probe->pid());
  EXPECT_EQ(sample.value, 0.5);

  ASSERT_TRUE(probe->signal(SIGTERM));
  auto status = probe->wait(kBound);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << probe->stderr_text();
}

// Discovery across processes: the probe's endpoints are seen, with its name, and not as local.
TEST(TestDomainEnv, DiscoverySeesAnotherProcessAsRemote) {
  auto domain = TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  auto participant = dds::Participant::create(domain->config(), "discovery_observer");
  ASSERT_TRUE(participant) << participant.error().message;
  auto probe =
      ChildProcess::start(HUBRT_DDS_ENV_PROBE, {"--read", "/hubrt_test/remote_topic"}, domain->env());
  ASSERT_TRUE(probe) << probe.error().message;
  ASSERT_TRUE(probe->wait_for_output("probe: reading", kBound)) << probe->stderr_text();

  // Remote discovery is asynchronous, and a snapshot is not atomic: it reads the participants
  // before the endpoints, so one snapshot can hold the probe's reader but not yet its participant.
  // Poll until one snapshot holds both (CI once caught the reader alone).
  const auto holds_the_probe = [](const dds::DiscoverySnapshot& s) {
    bool reader = false;
    for (const auto& t : s.topics()) {
      if (t.topic_name == "rt/hubrt_test/remote_topic" && t.readers == 1) reader = true;
    }
    bool named = false;
    for (const auto& p : s.participants) {
      if (p.name == "hubrt_dds_env_probe") named = true;
    }
    return reader && named;
  };
  const auto deadline = std::chrono::steady_clock::now() + kBound;
  std::optional<dds::DiscoverySnapshot> seen;
  while (!seen && std::chrono::steady_clock::now() < deadline) {
    auto snapshot = dds::discover(*participant);
    ASSERT_TRUE(snapshot) << snapshot.error().message;
    if (holds_the_probe(*snapshot)) {
      seen = std::move(*snapshot);
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  ASSERT_TRUE(seen) << "the probe's reader and its named participant were never discovered together";
  for (const auto& t : seen->topics()) {
    if (t.topic_name != "rt/hubrt_test/remote_topic") continue;
    EXPECT_EQ(t.type_name, "hubrt_test::msg::dds_::Counter_");
    EXPECT_EQ(t.local_readers, 0u);
    ASSERT_EQ(t.participant_keys.size(), 1u);
    EXPECT_NE(t.participant_keys[0], participant->guid());
  }
  bool probe_listed = false;
  for (const auto& p : seen->participants) {
    if (p.name == "hubrt_dds_env_probe") {
      probe_listed = true;
      EXPECT_FALSE(p.local);
    }
    if (p.key == participant->guid()) {
      EXPECT_TRUE(p.local);
    }
  }
  EXPECT_TRUE(probe_listed) << "the probe's participant name travels with discovery";
}

}  // namespace
}  // namespace hubrt::test_support
