// The loopback configuration (dds::loopback_config_xml, what TestDomain and `--loopback` use)
// admits a station's worth of processes of one domain on one host: 64 hubs, hubctl and a planner,
// 66 participants. Cyclone's participant index decides each one's unicast ports, and a host admits
// MaxAutoParticipantIndex of them (firmware/dds/src/domain.cc); with the old bound of 32 the 33rd
// process, e.g. hubctl beside 32 hubs, could not join ("Failed to find a free participant index").
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <vector>

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include "hubrt/dds/participant.h"
#include "hubrt/dds/ports.h"
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

// Generous: the probe's start-up and discovery on a busy 2-core machine, possibly under a
// sanitizer; the test waits on events and only gives up at this bound.
constexpr Duration kCapacityBound = std::chrono::seconds(30);

constexpr int kHubs = 64;

// Cyclone's default port mapping (DDSI 2.x section 9.6.1.1; Discovery/Ports in Cyclone 0.10.2
// ddsi_cfgelems.h: Base 7400, DomainGain 250, ParticipantGain 2, d1 10): the unicast discovery
// port of a participant index. Cyclone takes the first index whose ports it can bind
// (q_init.c, make_uc_sockets: EADDRINUSE means "in use, try the next").
std::uint16_t unicast_discovery_port(std::uint32_t domain_id, int index) {
  return static_cast<std::uint16_t>(dds::unicast_discovery_port(domain_id, index));
}

// UDP sockets bound to the discovery ports of participant indices 0..count-1: to Cyclone, as
// many processes of the domain already on this host (a hub each), without starting 64 hubs.
class TakenIndices {
 public:
  TakenIndices(std::uint32_t domain_id, int count) {
    for (int index = 0; index < count; ++index) {
      const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
      if (fd < 0) continue;
      sockaddr_in address{};
      address.sin_family = AF_INET;
      // Cyclone binds its unicast receive sockets to any address without SO_REUSEADDR
      // (ddsi_udp.c, ddsi_udp_create_conn, DDSI_TRAN_QOS_RECV_UC): the same bind here makes its
      // bind of this port fail.
      address.sin_addr.s_addr = htonl(INADDR_ANY);
      address.sin_port = htons(unicast_discovery_port(domain_id, index));
      // A port already in use is as taken to Cyclone as one bound here. The test domains' ports
      // lie in Linux's ephemeral range (32768-60999), where another test's socket can sit: CI once
      // found one of these 64 ports held so (a fresh clone's .ci/run, TSan tests at -j2).
      if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0 ||
          errno == EADDRINUSE) {
        ++taken_;
      }
      fds_.push_back(fd);
    }
  }
  ~TakenIndices() {
    for (const int fd : fds_) ::close(fd);
  }
  TakenIndices(const TakenIndices&) = delete;
  TakenIndices& operator=(const TakenIndices&) = delete;
  // Indices whose discovery port is bound here or was in use already.
  [[nodiscard]] int taken() const { return taken_; }

 private:
  std::vector<int> fds_;
  int taken_ = 0;
};

TEST(LoopbackCapacity, SixtyFourHubsHubctlAndAPlannerOnOneHostFindEachOther) {
  auto domain = TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  const TakenIndices hubs(domain->domain_id(), kHubs);
  ASSERT_EQ(hubs.taken(), kHubs) << "every one of the first 64 indices should be taken";

  // The 65th participant (hubctl's place): index 64.
  ProbeListener listener;
  {
    SCOPED_TRACE("the 65th participant on the host");
    ASSERT_NO_FATAL_FAILURE(open_probe_listener(*domain, "loopback_capacity_test", listener));
  }

  // The 66th (a planner's place), in another process: index 65. Its sample arriving shows both
  // joined and found each other through the unicast discovery peers of these high indices.
  auto probe = ChildProcess::start(HUBRT_DDS_ENV_PROBE, {}, domain->env());
  ASSERT_TRUE(probe) << probe.error().message;
  std::array<dds::WaitSet::Token, 1> fired{};
  auto n = listener.waitset->wait(fired, kCapacityBound);
  ASSERT_TRUE(n.is_ok());
  ASSERT_EQ(n.value(), 1u) << "no sample from the 66th participant; its output:\n"
                           << probe->stdout_text() << probe->stderr_text();
  Counter sample{};
  auto taken = listener.reader->take_next(sample);
  ASSERT_TRUE(taken.is_ok());
  ASSERT_TRUE(taken.value());
  EXPECT_EQ(sample.count, probe->pid());
  ASSERT_TRUE(probe->signal(SIGTERM));
  auto status = probe->wait(kCapacityBound);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << probe->stderr_text();
}

}  // namespace
}  // namespace hubrt::test_support
