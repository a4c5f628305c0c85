// A private loopback domain and one participant in it, for every test that moves DDS traffic.
#pragma once

#include <signal.h>

#include <array>
#include <chrono>
#include <optional>

#include <gtest/gtest.h>

#include "hubrt/dds/participant.h"
#include "hubrt/dds/read_condition.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/waitset.h"
#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/test_domain.h"

namespace hubrt::dds::test {

// Upper bound for anything that waits on DDS within one process (discovery, delivery). Normally
// milliseconds; generous because sanitizer builds on a loaded 2-core machine are slow, and tests
// wait on events, so the bound is only reached when something is broken.
inline constexpr Duration kDeliveryBound = std::chrono::seconds(20);

class DdsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = Participant::create(domain_->config(), "dds_test");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
  }

  Participant& participant() { return *participant_; }
  [[nodiscard]] DomainConfig config() const { return domain_->config(); }

  // Blocks until `reader` holds at least one sample (bounded by kDeliveryBound); true if it does.
  // `owner` is the participant the reader was created from (a waitset and its conditions must
  // belong to the same participant).
  template <class R>
  bool wait_for_data(const R& reader) {
    return wait_for_data(reader, participant());
  }
  template <class R>
  static bool wait_for_data(const R& reader, const Participant& owner) {
    auto condition = ReadCondition::create(reader);
    auto waitset = WaitSet::create(owner);
    if (!condition || !waitset || !waitset->attach(*condition, 1)) return false;
    std::array<WaitSet::Token, 1> fired{};
    const auto n = waitset->wait(fired, kDeliveryBound);
    return n.is_ok() && n.value() == 1 && fired[0] == 1;
  }

  // Ends the DDS peer process (tests/support/test/dds_env_probe.cc) and expects it to exit 0, as
  // it does after SIGTERM unless DDS failed in it.
  static void expect_probe_ends_cleanly(test_support::ChildProcess& probe) {
    ASSERT_TRUE(probe.signal(SIGTERM));
    auto status = probe.wait(kDeliveryBound);
    ASSERT_TRUE(status) << status.error().message;
    EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << probe.stderr_text();
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<Participant> participant_;
};

}  // namespace hubrt::dds::test
