// `hubctl send --once` reaches every reader on the domain, not only the first one matched: the
// readers here are three `hubctl echo` processes (each its own DDS participant, as three hubs'
// sim bridges are), on /sim/fault as in a fault scenario. And `--wait N` waits for N readers,
// or fails clearly with nothing sent.
#include <csignal>
#include <cstdio>
#include <optional>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/dds/discovery.h"
#include "hubrt/dds/participant.h"
#include "hubrt/test_support/hub_process.h"

namespace hubrt::integration {
using test_support::Finished;
namespace {

using std::chrono::seconds;
using test_support::ChildProcess;

constexpr const char* kFaultType = "hub_msgs/msg/SimFault";

class HubctlSendTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto observer = dds::Participant::create(domain_->config(), "test-observer");
    ASSERT_TRUE(observer) << observer.error().message;
    observer_.emplace(std::move(*observer));
  }

  // A reader of /sim/fault in a process of its own that prints the first sample and exits.
  ChildProcess start_reader() {
    auto child = ChildProcess::start(
        HUBRT_HUBCTL_PATH, {"echo", "/sim/fault", "--type", kFaultType, "--count", "1", "--timeout", "120"},
        domain_->env());
    EXPECT_TRUE(child) << child.error().message;
    return std::move(*child);
  }

  std::vector<ChildProcess> start_readers(std::size_t count) {
    std::vector<ChildProcess> readers;
    readers.reserve(count + 1);  // room for a late one
    for (std::size_t i = 0; i < count; ++i) readers.push_back(start_reader());
    return readers;
  }

  // Waits until the observer has discovered `count` readers of /sim/fault: the hubs are up before
  // anyone sends them a fault. 60 s: start-up under sanitizers on a loaded machine is slow.
  void await_readers(std::size_t count) { await_endpoints(dds::EndpointDirection::kReader, count); }

  void await_endpoints(dds::EndpointDirection direction, std::size_t count) {
    const auto deadline = std::chrono::steady_clock::now() + seconds(60);
    std::size_t found = 0;
    while (std::chrono::steady_clock::now() < deadline) {
      auto snapshot = dds::discover(*observer_);
      ASSERT_TRUE(snapshot) << snapshot.error().message;
      found = 0;
      for (const auto& e : snapshot->endpoints) {
        found += !e.local && e.direction == direction && e.topic_name == "rt/sim/fault";
      }
      if (found >= count) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    FAIL() << "only " << found << " of " << count << " endpoints on /sim/fault appeared";
  }

  ChildProcess start_send(const std::vector<std::string>& extra) {
    std::vector<std::string> args = {
        "send",          "/sim/fault",          "--type", kFaultType, "hub=dock_ecu",
        "device=supply", "fault=pressure_drop", "value=7"};
    args.insert(args.end(), extra.begin(), extra.end());
    auto child = ChildProcess::start(HUBRT_HUBCTL_PATH, args, domain_->env());
    EXPECT_TRUE(child) << child.error().message;
    return std::move(*child);
  }

  static Finished finish(ChildProcess& child, Duration timeout) {
    auto status = child.wait(timeout);
    EXPECT_TRUE(status) << status.error().message << "\n" << child.stdout_text() << child.stderr_text();
    return Finished{status ? *status : test_support::ExitStatus{}, child.stdout_text() + child.stderr_text()};
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> observer_;
};

// Before: send matched the first reader, wrote once and left after 100 ms; the readers matched
// after the write never got the fault. (--type makes send create its writer before discovery
// has found anyone, as with hubs that are busy answering several new participants.)
TEST_F(HubctlSendTest, OnceReachesEveryReaderOnTheDomain) {
  std::vector<ChildProcess> readers = start_readers(3);
  await_readers(3);
  // No LIFESPAN: the subject is reaching every reader, however slowly a loaded machine lets them
  // match and acknowledge; what a LIFESPAN adds is AnAcknowledgementPastTheLifespanIsReported's.
  ChildProcess send = start_send({"--once", "--timeout", "30", "--lifespan-ms", "0"});
  const Finished sent = finish(send, seconds(60));
  EXPECT_TRUE(sent.status.exited_with(0)) << sent.status.describe() << "\n" << sent.output;
  EXPECT_NE(sent.output.find("sent 1 sample(s) to 3 reader(s); all acknowledged"), std::string::npos)
      << sent.output;
  for (std::size_t i = 0; i < readers.size(); ++i) {
    // Acknowledged means in the reader's cache: echo prints it and exits at once. The bound
    // only covers a loaded machine.
    const Finished got = finish(readers[i], seconds(30));
    EXPECT_TRUE(got.status.exited_with(0)) << "reader " << i << ": " << got.status.describe() << "\n"
                                           << got.output;
    EXPECT_NE(got.output.find("pressure_drop"), std::string::npos) << "reader " << i << ":\n" << got.output;
  }
}

TEST_F(HubctlSendTest, WaitForMoreReadersThanThereAreFailsWithNothingSent) {
  std::vector<ChildProcess> readers = start_readers(2);
  await_readers(2);
  ChildProcess send = start_send({"--once", "--wait", "3", "--timeout", "2"});
  const Finished sent = finish(send, seconds(60));
  EXPECT_TRUE(sent.status.exited_with(1)) << sent.status.describe() << "\n" << sent.output;
  EXPECT_NE(
      sent.output.find("hubctl send: only 2 of 3 reader(s) of /sim/fault matched within 2.0 s; nothing sent"),
      std::string::npos)
      << sent.output;
  for (ChildProcess& reader : readers) {
    EXPECT_EQ(reader.stdout_text().find("pressure_drop"), std::string::npos) << reader.stdout_text();
  }
}

// Before: a warning, the sample sent into the void, and exit 0.
TEST_F(HubctlSendTest, OnceWithNobodyListeningFailsWithNothingSent) {
  ChildProcess send = start_send({"--once", "--timeout", "1"});
  const Finished sent = finish(send, seconds(60));
  EXPECT_TRUE(sent.status.exited_with(1)) << sent.status.describe() << "\n" << sent.output;
  EXPECT_NE(sent.output.find("hubctl send: nobody reads /sim/fault (waited 1.0 s); nothing sent"),
            std::string::npos)
      << sent.output;
}

TEST_F(HubctlSendTest, CtrlCWhileWaitingForReadersSaysInterruptedAndExits130) {
  ChildProcess send = start_send({"--once", "--wait", "2", "--timeout", "120"});
  // Its writer exists once its Ctrl-C handler does; no reader ever comes, so it is waiting.
  await_endpoints(dds::EndpointDirection::kWriter, 1);
  EXPECT_TRUE(send.signal(SIGINT));
  const Finished sent = finish(send, seconds(60));
  EXPECT_TRUE(sent.status.exited_with(130)) << sent.status.describe() << "\n" << sent.output;
  EXPECT_NE(
      sent.output.find("hubctl send: interrupted while waiting for readers of /sim/fault; nothing sent"),
      std::string::npos)
      << sent.output;
}

// The third hub comes up while send waits for it: it gets the fault too. Two races behind it,
// both seen only under load, both with send printing "all acknowledged" and the late reader
// never printing the fault (CI twice, here once): send's writer can match the late reader before
// the reader matches it back, and a reader drops, and acknowledges, what a writer wrote before
// the reader heard its first heartbeat (dds::UntypedWriter::announce: send now announces itself
// and waits for every matched reader to acknowledge that); and echo's tap took the sample into
// no queue when it came before echo subscribed (StationTap: it now takes nothing before then).
TEST_F(HubctlSendTest, WaitForNReadersWaitsForALateOne) {
  std::vector<ChildProcess> readers = start_readers(2);
  await_readers(2);
  // No LIFESPAN: a reader that is slow to acknowledge is then slow, not a gap (the test below).
  ChildProcess send = start_send({"--once", "--wait", "3", "--timeout", "60", "--lifespan-ms", "0"});
  // Long enough for send to have matched the first two and be waiting (it would have written by
  // now without --wait); the reader's own start-up adds more.
  std::this_thread::sleep_for(seconds(2));
  EXPECT_EQ(send.stdout_text().find("sent 1"), std::string::npos) << send.stdout_text();
  readers.push_back(start_reader());
  const Finished sent = finish(send, seconds(90));
  EXPECT_TRUE(sent.status.exited_with(0)) << sent.status.describe() << "\n" << sent.output;
  EXPECT_NE(sent.output.find("sent 1 sample(s) to 3 reader(s); all acknowledged"), std::string::npos)
      << sent.output;
  for (std::size_t i = 0; i < readers.size(); ++i) {
    const Finished got = finish(readers[i], seconds(30));
    EXPECT_TRUE(got.status.exited_with(0)) << "reader " << i << ": " << got.status.describe() << "\n"
                                           << got.output;
    EXPECT_NE(got.output.find("pressure_drop"), std::string::npos) << "reader " << i << ":\n" << got.output;
  }
}

// A reader that acknowledges only after the sample's LIFESPAN may have had a gap in its place:
// send says so instead of "all acknowledged". The default LIFESPAN (1000 ms), two samples 5 s
// apart: the reader prints the first, and is then stopped (SIGSTOP) from before the second write
// until 3 s or more after it, so its acknowledgement of the last sample cannot be in time. (A
// reader stopped before matching could not match at all.)
TEST_F(HubctlSendTest, AnAcknowledgementPastTheLifespanIsReported) {
  auto started = ChildProcess::start(
      HUBRT_HUBCTL_PATH, {"echo", "/sim/fault", "--type", kFaultType, "--count", "2", "--timeout", "120"},
      domain_->env());
  ASSERT_TRUE(started) << started.error().message;
  ChildProcess& reader = *started;
  await_readers(1);
  ChildProcess send = start_send({"--count", "2", "--rate", "0.2", "--wait", "1", "--timeout", "60"});
  // 60 s: start-up under sanitizers on a loaded machine.
  ASSERT_TRUE(reader.wait_for_output("pressure_drop", seconds(60)))
      << reader.stdout_text() << reader.stderr_text() << send.stdout_text() << send.stderr_text();
  ASSERT_TRUE(reader.signal(SIGSTOP));
  std::this_thread::sleep_for(seconds(8));
  EXPECT_TRUE(reader.signal(SIGCONT));
  const Finished sent = finish(send, seconds(60));
  EXPECT_TRUE(sent.status.exited_with(0)) << sent.status.describe() << "\n" << sent.output;
  EXPECT_NE(sent.output.find("after it was written, past its 1000 ms LIFESPAN"), std::string::npos)
      << sent.output;
  EXPECT_NE(sent.output.find("sent 2 sample(s) to 1 reader(s); acknowledged past the LIFESPAN"),
            std::string::npos)
      << sent.output;
  EXPECT_EQ(sent.output.find("all acknowledged"), std::string::npos) << sent.output;
  // The figure is the stopped reader's, not the 1 s expiry's: Cyclone waits for every matched
  // reader's acknowledgement (dds_wait_for_acks), and the reader stayed stopped 3 s past the write.
  double delay_s = 0.0;
  const auto at = sent.output.find("was acknowledged ");
  ASSERT_NE(at, std::string::npos) << sent.output;
  ASSERT_EQ(std::sscanf(sent.output.c_str() + at, "was acknowledged %lf s after", &delay_s), 1)
      << sent.output;
  EXPECT_GE(delay_s, 2.0) << sent.output;
}

}  // namespace
}  // namespace hubrt::integration
