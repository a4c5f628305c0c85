// `hubctl send` writes commands with LIFESPAN (--lifespan-ms, default 1000 ms: the default command
// timeout), announced to the readers with the writer's QoS: a reader that has not taken a command
// within the lifespan of receiving it never gets it (Cyclone 0.10.2 drops it from the reader's
// history: dds_rhc_default.c, dds_rhc_default_sample_expired_cb, with the expiry set at reception,
// ddsi_endpoint.c ddsi_make_writer_info). The reader here is the test's, in its own process,
// taking late on purpose; with --lifespan-ms 0 the same late take still finds the command.
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"

#include "dock_messages.h"
#include "hubrt/test_support/hub_process.h"

namespace hubrt::integration {
namespace {


using dock_ecu::DockCommand;
using std::chrono::milliseconds;
using std::chrono::seconds;

class HubctlLifespanTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "test-late-reader");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    topic_.emplace(*dds::Topic<DockCommand>::create(*participant_, "/dock/command"));
    reader_.emplace(*dds::Reader<DockCommand>::create(*participant_, *topic_));
  }

  // Sends one command with --lifespan-ms `lifespan_ms` and waits until hubctl is done (every
  // reader acknowledged it: it is in the reader's history), then how many the reader takes
  // `late` afterwards.
  int taken_after(const std::string& lifespan_ms, Duration late) {
    auto send = test_support::ChildProcess::start(
        HUBRT_HUBCTL_PATH,
        {"send", "/dock/command", "--type", "hub_msgs/msg/DockCommand", "target_type=dock",
         "target_name=dock", "action=monitor", "--once", "--lifespan-ms", lifespan_ms, "--timeout", "20"},
        domain_->env());
    EXPECT_TRUE(send) << send.error().message;
    auto status = send->wait(seconds(60));
    EXPECT_TRUE(status && status->exited_with(0)) << send->stdout_text() << send->stderr_text();
    std::this_thread::sleep_for(late);
    int taken = 0;
    while (reader_->take_next(sample_).value_or(false)) ++taken;
    return taken;
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<DockCommand>> topic_;
  std::optional<dds::Reader<DockCommand>> reader_;
  dds::Sample<DockCommand> sample_;
};

TEST_F(HubctlLifespanTest, ACommandNotTakenWithinItsLifespanIsNeverDelivered) {
  EXPECT_EQ(taken_after("300", milliseconds(800)), 0) << "expired 300 ms after it was received";
}

TEST_F(HubctlLifespanTest, WithoutLifespanTheLateTakeStillFindsIt) {
  EXPECT_EQ(taken_after("0", milliseconds(800)), 1);
}

TEST_F(HubctlLifespanTest, WithinItsLifespanItIsDelivered) {
  EXPECT_EQ(taken_after("5000", milliseconds(300)), 1);
}

}  // namespace
}  // namespace hubrt::integration
