// The tool changer's cycle publishing through the REAL State path — assembly's DdsStateSink over a
// dds::Writer<RspState>, with a subscriber in this test taking every sample — allocates nothing,
// where Cyclone's own dds_write of the same sample allocates twice (Cyclone 0.10.2,
// src/core/ddsi/src/ddsi_serdata_default.c: serdata_default_new starts every serialised sample at
// 128 bytes (DEFAULT_NEW_SIZE), taken from a freelist or malloc'ed, serdata_default_append reallocs
// it larger, and serdata_default_free returns only those of at most 256 bytes (MAX_SIZE_FOR_POOL)
// to the freelist — a malloc and a realloc per write). The writer serialises into its pool of
// serdata and writes them with dds_writecdr (firmware/dds/src/serdata_pool.cc). Cyclone's own
// write is measured in the same test as the reference: every cycle is followed by a raw dds_write
// of the very State the cycle just published, counted apart.
#include <gtest/gtest.h>
#include <spdlog/sinks/null_sink.h>
#include <spdlog/spdlog.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/fake_backend.h"
#include "hubrt/hub_api/dds_ports.h"
#include "hubrt/hub_api/node_wiring.h"
#include "hubrt/runtime/hub.h"
#include "hubrt/runtime/node.h"
#include "hubrt/test_support/test_domain.h"

#include "alloc_counter.h"
#include "rsp_logic.h"
#include "rsp_test_support.h"

namespace hubrt::rsp_ecu {
namespace {

using hubrt::testing::AllocationScope;
using std::chrono::milliseconds;
using testing::command;
using testing::dock_slots;
using testing::DockFeed;
using testing::OwnedCommand;
using testing::QueueSource;

// Discovery within one process; generous because sanitizer builds on a loaded 2-core machine are
// slow. Only reached when something is broken.
constexpr Duration kMatchBound = std::chrono::seconds(20);

// The shipped board and hub file on the fake backend: RspLogicTest's set-up.
class RspCycleWithDds : public testing::RspLogicTest {};

TEST_F(RspCycleWithDds, AllocatesNothingWhereCyclonesOwnWriteDoes) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  auto participant = dds::Participant::create(domain->config(), "rsp_alloc");
  ASSERT_TRUE(participant) << participant.error().message;
  auto topic = dds::Topic<RspState>::create(*participant, "/hubrt_test/rsp_alloc/state");
  ASSERT_TRUE(topic) << topic.error().message;
  auto writer = dds::Writer<RspState>::create(*participant, *topic);
  ASSERT_TRUE(writer) << writer.error().message;
  auto reader = dds::Reader<RspState>::create(*participant, *topic);
  ASSERT_TRUE(reader) << reader.error().message;
  ASSERT_TRUE(writer->wait_for_readers(1, kMatchBound));
  const dds_entity_t writer_handle = writer->handle();
  hub_api::DdsStateSink<RspState> sink(std::move(*writer));

  ManualClock& clock = clock_;
  DockFeed& dock = dock_;
  RspLogic logic = make_logic();
  ASSERT_FALSE(HasFailure());
  QueueSource source;
  runtime::NodeOptions options;
  options.name = "rsp";
  options.log = std::make_shared<spdlog::logger>("rsp", std::make_shared<spdlog::sinks::null_sink_mt>());
  runtime::Hub hub(runtime::HubOptions{"rsp_ecu", "rsp_alloc", milliseconds(10), options.log});
  auto owned_node = std::make_unique<runtime::Node<RspLogic>>(options, std::move(logic), source, sink,
                                                              hub_api::message_ops<RspCommand>());
  const runtime::Node<RspLogic>& node = *owned_node;
  hub.add_node(std::move(owned_node));

  // As in rsp_cycle_alloc_test: commands changing every 10 cycles, every unlock refused (reasons
  // formatted into the State's error_list), the Dock ECU going quiet after cycle 150.
  constexpr int kCycles = 300;
  const OwnedCommand commands[] = {command("lock", "grab"), command("lock", "keep"),
                                   command("unlock", "grab")};
  for (int i = 0; i < kCycles; ++i) source.push(commands[(i / 10) % 3]);
  dock.arrive(dock_slots(true, true, false), clock.now().mono);

  dds::Sample<RspState> taken;
  std::size_t received = 0;
  const auto take_all = [&] {
    while (reader->take_next(taken).value_or(false)) ++received;
  };
  std::size_t cycle_allocations = 0;
  std::size_t raw_write_allocations = 0;
  bool raw_writes_ok = true;
  const auto run = [&](int from, int to, bool count) {
    for (int i = from; i < to; ++i) {
      if (i < 150 && i % 10 == 0) dock.input().note_arrival(clock.now().mono);
      {
        const AllocationScope scope;
        hub.cycle(clock.now());  // steps the node and publishes its State through the sink
        if (count) cycle_allocations += scope.count();
      }
      take_all();  // the subscriber keeps up; its take is not what is measured
      {
        // Cyclone's own cost for the same sample: the State the cycle just published.
        const AllocationScope scope;
        raw_writes_ok &= dds_write(writer_handle, &node.state()) == DDS_RETCODE_OK;
        if (count) raw_write_allocations += scope.count();
      }
      take_all();
      clock.advance(milliseconds(10));
    }
  };
  run(0, 40, false);  // warm-up: first log messages and formats, Cyclone's first samples
  run(40, kCycles, true);

  const int measured = kCycles - 40;
  std::printf(
      "[alloc] %s: RspState cycle through DdsStateSink %zu, raw dds_write of the same State %zu "
      "(allocations in %d cycles/writes)\n",
      hubrt::testing::allocation_counting_method(), cycle_allocations, raw_write_allocations, measured);
  EXPECT_TRUE(raw_writes_ok);
  EXPECT_EQ(hub.stats().publish_errors, 0u);
  EXPECT_EQ(cycle_allocations, 0u) << "the cycle allocates (Cyclone's dds_write alone: "
                                   << raw_write_allocations << " in the same cycles)";
  // The real path ran: every State (the cycle's and the raw one) reached the subscriber, and the
  // interlock's refusals were in it.
  EXPECT_EQ(received, static_cast<std::size_t>(2 * kCycles));
  EXPECT_GT(node.rejected(), 0u);
  EXPECT_EQ(hub.stats().cycles, static_cast<std::uint64_t>(kCycles));
}

}  // namespace
}  // namespace hubrt::rsp_ecu
