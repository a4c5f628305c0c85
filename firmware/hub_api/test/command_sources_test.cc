// The command sources of both layouts hand each command over with the writer's source timestamp
// and the hub's wall clock read at the take (ports.h, ReceivedCommand::take_wall), so that a
// command written while the cycle thread was held between reading its clocks and taking is judged
// young, not "stamped in the future" (command_age.h). The clocks here are manual: the planner
// stamps its command from the same ManualClock, after the cycle's reading.
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/writer.h"
#include "hubrt/hub_api/dds_ports.h"
#include "hubrt/hub_api/hub_layout.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/runtime/command_age.h"
#include "hubrt/test_support/test_domain.h"

#include "dock_messages.h"

namespace hubrt::hub_api {
namespace {

using dock_ecu::DockCommand;
using std::chrono::milliseconds;

TEST(DdsCommandSource, ReportsTheHubsWallClockAtTheTakeWithTheSourceTimestamp) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  auto participant = dds::Participant::create(domain->config(), "dds_command_source_test");
  ASSERT_TRUE(participant) << participant.error().message;
  auto topic = dds::Topic<DockCommand>::create(*participant, "/dock_ecu/dock/command");
  ASSERT_TRUE(topic) << topic.error().message;
  auto reader =
      dds::Reader<DockCommand>::create(*participant, *topic, dds::Qos::ros2_default(kCommandHistoryDepth));
  ASSERT_TRUE(reader) << reader.error().message;
  auto writer = dds::Writer<DockCommand>::create(*participant, *topic, dds::Qos::ros2_default());
  ASSERT_TRUE(writer) << writer.error().message;
  ManualClock clock;
  DdsCommandSource<DockCommand> source(std::move(*reader), clock);

  const Instant cycle = clock.now();  // the cycle reads its clocks ...
  clock.advance(milliseconds(103));   // ... and is held before it takes
  DockCommand command{};
  msgs::typed::assign(command.action, "monitor");
  msgs::typed::assign(command.target_name, "dock");
  const WallTime written = clock.now().wall;
  ASSERT_TRUE(writer->write(command, written).is_ok());
  clock.advance(milliseconds(2));  // delivery
  const WallTime take_wall = clock.now().wall;

  // Delivery within one process is quick, but not synchronous: poll with a deadline.
  std::optional<runtime::ReceivedCommand<DockCommand>> received;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!received && std::chrono::steady_clock::now() < deadline) {
    auto next = source.next();
    ASSERT_TRUE(next.is_ok());
    if (next.value().command != nullptr) {
      received = next.value();
    } else {
      std::this_thread::sleep_for(milliseconds(1));
    }
  }
  ASSERT_TRUE(received) << "the command never arrived";
  EXPECT_STREQ(received->command->action, "monitor");
  ASSERT_TRUE(received->source_time.has_value());
  EXPECT_EQ(received->source_time->ns_since_epoch, written.ns_since_epoch);
  ASSERT_TRUE(received->take_wall.has_value()) << "the source reads its clock at the take";
  EXPECT_EQ(received->take_wall->ns_since_epoch, take_wall.ns_since_epoch);

  runtime::CommandAgeJudge judge(std::chrono::seconds(1), runtime::kDefaultClockTolerance);
  const runtime::JudgedAge judged =
      judge.judge(runtime::CommandTimes{received->source_time, cycle, received->take_wall});
  EXPECT_EQ(judged.verdict, runtime::AgeVerdict::kYoung)
      << "written after the cycle's reading, taken 2 ms later";
  EXPECT_EQ(judged.offset, milliseconds(2));
}

// The hub layout's fragments carry the hub command's times on to their nodes, which judge them as
// the hub-level node judged the hub command: against the wall clock of its take.
TEST(MailboxSource, HandsTheFragmentOnWithTheHubCommandsTimes) {
  ManualClock clock;
  MailboxSource<DockCommand> mailbox;
  auto none = mailbox.next();
  ASSERT_TRUE(none.is_ok());
  EXPECT_EQ(none.value().command, nullptr);

  const Instant cycle = clock.now();
  const WallTime written{cycle.wall.ns_since_epoch + milliseconds(100).count()};
  const WallTime take_wall{cycle.wall.ns_since_epoch + milliseconds(101).count()};
  DockCommand fragment{};
  msgs::typed::assign(fragment.action, "monitor");
  mailbox.post(fragment, runtime::CommandTimes{written, cycle, take_wall});
  auto next = mailbox.next();
  ASSERT_TRUE(next.is_ok());
  ASSERT_NE(next.value().command, nullptr);
  EXPECT_STREQ(next.value().command->action, "monitor");
  ASSERT_TRUE(next.value().source_time && next.value().take_wall);
  EXPECT_EQ(next.value().source_time->ns_since_epoch, written.ns_since_epoch);
  EXPECT_EQ(next.value().take_wall->ns_since_epoch, take_wall.ns_since_epoch);
  auto after = mailbox.next();
  ASSERT_TRUE(after.is_ok());
  EXPECT_EQ(after.value().command, nullptr) << "one fragment per post";
}

}  // namespace
}  // namespace hubrt::hub_api
