// The steady-state cycle allocates nothing: commands arriving (repeats and changes), the logic,
// the State rebuilt and published, the watchdog tripping and recovering.
#include <string>

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include "hubrt/runtime/hub.h"
#include "hubrt/runtime/reflected_message_ops.h"

#include "alloc_counter.h"
#include "node_test_support.h"
#include "valve_test_reflect.h"

namespace hubrt::runtime::testing {
namespace {

using hubrt::testing::AllocationScope;
using std::chrono::milliseconds;

TEST(AllocationCounter, SeesAnAllocation) {
  AllocationScope scope;
  auto* p = new std::string(100, 'x');  // NOLINT: deliberately allocating to prove the counter works
  delete p;                             // NOLINT
  EXPECT_GE(scope.count(), 2u);
}

TEST(SteadyCycle, AllocatesNothing) {
  ManualClock clock;
  ValveWorld world;
  QueueSource source;
  CountingSink sink;
  ReflectedMessageOps ops(msgs::type_info_of<ValveCommand>());
  Hub hub(HubOptions{"test", "hub", milliseconds(10), nullptr});
  NodeOptions options;
  options.name = "v1";
  options.command_timeout = milliseconds(100);
  auto node = std::make_unique<Node<ValveLogic>>(options, ValveLogic(world), source, sink, ops);
  const auto& node_ref = *node;
  hub.add_node(std::move(node));

  // Queue every command up front (the queue itself allocates); the planner changes its command
  // every 10 cycles and goes silent for 30 cycles in the middle, tripping the watchdog.
  constexpr int kCycles = 600;
  std::vector<bool> has_command(kCycles, false);
  std::vector<std::size_t> delivered_by(kCycles, 0);  // commands handed out up to cycle i
  std::size_t queued = 0;
  for (int i = 0; i < kCycles; ++i) {
    delivered_by[static_cast<std::size_t>(i)] = queued;
    if (i >= 300 && i < 330) continue;
    OwnedValveCommand command;
    command.action = (i / 10) % 2 == 0 ? "open" : "close";
    command.pressure_bar = static_cast<float>((i / 10) % 7);
    command.tags = {"station-1", "bolt pair " + std::to_string(i / 10)};
    source.push(command);
    has_command[static_cast<std::size_t>(i)] = true;
    delivered_by[static_cast<std::size_t>(i)] = ++queued;
  }
  // Warm-up. spdlog sizes its formatting caches on a logger's first message (hubd logs at start-up
  // long before its first cycle); after that, logging an event allocates nothing.
  spdlog::info("steady cycle allocation test: start");
  for (int i = 0; i < 5; ++i) {
    source.deliver_up_to(delivered_by[static_cast<std::size_t>(i)]);
    hub.cycle(clock.now());
    clock.advance(milliseconds(10));
  }

  AllocationScope scope;
  for (int i = 5; i < kCycles; ++i) {
    source.deliver_up_to(delivered_by[static_cast<std::size_t>(i)]);
    if (has_command[static_cast<std::size_t>(i)] && i % 3 == 0) {
      hub.command_step(clock.now());  // some commands are served between cycles
    }
    hub.cycle(clock.now());
    clock.advance(milliseconds(10));
  }
  const std::size_t allocations = scope.count();

  EXPECT_EQ(allocations, 0u);
  // It really ran: states published, the watchdog tripped and the node recovered.
  EXPECT_GE(sink.count, static_cast<std::uint64_t>(kCycles - 5));
  EXPECT_GT(world.updates_without_command, 0);
  EXPECT_TRUE(node_ref.state().fresh_msg());
  EXPECT_EQ(node_ref.rejected(), 0u);
}

// Issue 11's hostile inputs on the cycle path: a flood of alternating commands (the budget
// holds States back) and commands with bad UTF-8 and control characters (rejected, quoted
// escaped into error_list) allocate nothing either.
TEST(SteadyCycle, AFloodAndBadCommandTextAllocateNothing) {
  ManualClock clock;
  ValveWorld world;
  QueueSource source;
  CountingSink sink;
  ReflectedMessageOps ops(msgs::type_info_of<ValveCommand>());
  Hub hub(HubOptions{"test", "hub", milliseconds(10), nullptr});
  NodeOptions options;
  options.name = "v1";
  options.command_timeout = milliseconds(100);
  auto node = std::make_unique<Node<ValveLogic>>(options, ValveLogic(world), source, sink, ops);
  const auto& node_ref = *node;
  hub.add_node(std::move(node));

  constexpr std::size_t kCommands = 2000;
  for (std::size_t i = 0; i < kCommands; ++i) {
    OwnedValveCommand command;
    command.action = i % 2 == 0 ? "open" : "close";
    if (i % 10 == 3)
      command.action =
          "op\xed\xa0\x80"
          "en";                                                      // encoded surrogate
    if (i % 10 == 7) command.tags = {"ok", "line\nbreak \xc0\xaf"};  // control character, overlong
    source.push(command);
  }
  source.deliver_up_to(0);
  spdlog::info("flood allocation test: start");  // spdlog's caches, as in the test above
  for (int i = 0; i < 5; ++i) {
    hub.cycle(clock.now());
    clock.advance(milliseconds(10));
  }

  AllocationScope scope;
  for (std::size_t i = 0; i < kCommands; ++i) {
    source.deliver_up_to(i + 1);
    hub.command_step(clock.now());  // a command every 100 us: 10 kHz
    clock.advance(std::chrono::microseconds(100));
    if (i % 100 == 99) hub.cycle(clock.now());
  }
  const std::size_t allocations = scope.count();

  EXPECT_EQ(allocations, 0u);
  EXPECT_GT(node_ref.states_deferred(), 1000u) << "the budget held States back";
  EXPECT_GE(node_ref.rejected(), kCommands / 5) << "the bad commands were rejected";
}

}  // namespace
}  // namespace hubrt::runtime::testing
