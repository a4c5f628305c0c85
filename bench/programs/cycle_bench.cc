// Micro-benchmarks of the fixed-rate cycle with real DDS in the loop (Google Benchmark):
//   BM_HubCycle_Repeating   a Dock ECU hub assembled in this process on the fake backend, a planner
//                           thread repeating one command every 10 ms
//   BM_HubCycle_Changing    the same, the planner alternating two commands (each takes effect)
//   BM_RawStateWrite        the baseline: dds_write of the same DockState on the C API, same QoS,
//                           its instance registered as hubrt's Writer did before its write pool
//   BM_PooledStateWrite     hubrt's dds::Writer::write of the same DockState: Cyclone's serialiser
//                           into the writer's pool of serdata, written with dds_writecdr
// each with the State's subscriber (the argument) nowhere (0), in this process (1) or in another
// process (2, hubrt_bench_raw_peer sink: the hub's real situation). Each iteration is paced at
// 1 kHz (a real hub does not spin) and timed alone (manual time). Counters:
//   allocs_per_cycle          heap allocations on the cycle's thread, per cycle (the design says 0)
//   process_allocs_per_cycle  all threads, Cyclone's receive and delivery threads included, but the
//                             planner's: in a station the planner is another process, and a raw
//                             dds_write delivers to this process's readers on the writer's own
//                             thread, with Cyclone's serdata allocations now and then (in some runs
//                             about 46 per second, in others none)
//   planner_allocs_per_cycle  the planner thread's, apart
#include <pthread.h>

#include <array>
#include <atomic>
#include <ctime>
#include <optional>
#include <thread>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "hubrt/assembly/fake_simulation.h"
#include "hubrt/assembly/hub_assembly.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/test_support/test_domain.h"

#include "alloc_counter.h"
#include "bench_common.h"
#include "dock.h"
#include "dock_typed.h"
#include "raw_dds.h"

namespace hubrt::bench {
namespace {

using hubrt::testing::named_thread_allocations;
using hubrt::testing::process_allocations;
using hubrt::testing::thread_allocations;

constexpr const char* kPlannerThread = "planner";

constexpr std::int64_t kPeriodNs = 1'000'000;  // 1 kHz pacing
constexpr int kWarmupCycles = 300;

void sleep_until(timespec& next) {
  next.tv_nsec += kPeriodNs;
  if (next.tv_nsec >= 1'000'000'000) {
    next.tv_nsec -= 1'000'000'000;
    ++next.tv_sec;
  }
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr) == EINTR) {
  }
}

// The planner: writes a DockCommand every 10 ms on its own thread.
class Planner {
 public:
  Planner(dds_entity_t participant, bool changing) : changing_(changing) {
    auto writer = raw_writer(participant, hub_msgs_msg_dds__DockCommand__desc, "rt/dock/command");
    if (writer) writer_ = *writer;
    thread_ = std::thread([this] { run(); });
  }
  ~Planner() {
    stop_ = true;
    thread_.join();
  }
  Planner(const Planner&) = delete;
  Planner& operator=(const Planner&) = delete;

 private:
  void run() {
    pthread_setname_np(pthread_self(), kPlannerThread);
    hub_msgs_msg_dds__DockCommand_ command{};
    hubrt::msgs::typed::assign(command.target_type, "dock");
    hubrt::msgs::typed::assign(command.target_name, "dock");
    hubrt::msgs::typed::assign(command.action, "monitor");
    // Registered, as hubrt's writers hold their instance: the planner's own writes then allocate
    // nothing either (it runs in the measured process).
    dds_instance_handle_t instance = 0;
    dds_register_instance(writer_, &instance, &command);
    for (int i = 0; !stop_; ++i) {
      hubrt::msgs::typed::assign(command.action, changing_ && i % 2 == 1 ? "reset" : "monitor");
      dds_write(writer_, &command);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  bool changing_;
  dds_entity_t writer_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Where the State goes: nowhere, to a reader in this process, or to a reader in another process.
class Subscriber {
 public:
  enum Kind : std::int64_t { kNone = 0, kInProcess = 1, kOtherProcess = 2 };
  static const char* label(std::int64_t kind) {
    if (kind == kNone) return "no subscriber";
    return kind == kInProcess ? "subscriber in this process" : "subscriber in another process";
  }

  Subscriber() = default;
  Subscriber(const Subscriber&) = delete;
  Subscriber& operator=(const Subscriber&) = delete;
  ~Subscriber() {
    draining_ = false;
    if (thread_.joinable()) thread_.join();
    if (process_) stop(*process_);
  }

  // Returns what went wrong, or nothing.
  std::string start(std::int64_t kind, dds_entity_t participant, const test_support::TestDomain& domain,
                    const std::string& topic) {
    if (kind == kInProcess) {
      auto reader = raw_reader(participant, hub_msgs_msg_dds__DockState__desc, topic);
      if (!reader) return reader.error().message;
      reader_ = *reader;
      thread_ = std::thread([this] {
        void* samples[16] = {};
        dds_sample_info_t infos[16];
        while (draining_) {
          const dds_return_t n = dds_take(reader_, samples, infos, 16, 16);
          if (n > 0) dds_return_loan(reader_, samples, n);
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
      });
    } else if (kind == kOtherProcess) {
      auto child =
          test_support::ChildProcess::start(HUBRT_RAW_PEER_PATH, {"sink", "--topic", topic}, domain.env());
      if (!child) return child.error().message;
      if (!child->wait_for_output("raw sink matched", std::chrono::seconds(20)))
        return "the subscriber process never matched: " + child->stderr_text();
      process_.emplace(std::move(*child));
    }
    return {};
  }

 private:
  dds_entity_t reader_ = 0;
  std::atomic<bool> draining_{true};
  std::thread thread_;
  std::optional<test_support::ChildProcess> process_;
};

// Runs `step` once per iteration at 1 kHz and sets the counters.
template <class Step>
void paced(benchmark::State& state, Step&& step) {
  timespec next{};
  clock_gettime(CLOCK_MONOTONIC, &next);
  for (int i = 0; i < kWarmupCycles; ++i) {
    step();
    sleep_until(next);
  }
  std::uint64_t thread_allocs = 0;
  const std::uint64_t process_before = process_allocations();
  const std::uint64_t planner_before = named_thread_allocations(kPlannerThread);
  std::int64_t steps = 0;
  for (auto _ : state) {
    const std::uint64_t before = thread_allocations();
    const auto start = std::chrono::steady_clock::now();
    step();
    const auto end = std::chrono::steady_clock::now();
    thread_allocs += thread_allocations() - before;
    state.SetIterationTime(std::chrono::duration<double>(end - start).count());
    ++steps;
    sleep_until(next);
  }
  const auto n = static_cast<double>(steps);
  state.counters["allocs_per_cycle"] = static_cast<double>(thread_allocs) / n;
  const std::uint64_t planner = named_thread_allocations(kPlannerThread) - planner_before;
  state.counters["process_allocs_per_cycle"] =
      static_cast<double>(process_allocations() - process_before - planner) / n;
  state.counters["planner_allocs_per_cycle"] = static_cast<double>(planner) / n;
}

void hub_cycle(benchmark::State& state, bool changing) {
  auto domain = test_support::TestDomain::acquire();
  if (!domain) return state.SkipWithError(domain.error().message.c_str());
  SystemClock clock;
  assembly::AssemblyRequest request;
  request.board_file = std::string(HUBRT_SOURCE_DIR) + "/boards/host-sim.yaml";
  request.hub_file = std::string(HUBRT_SOURCE_DIR) + "/hubs/dock_ecu/dock_ecu.yaml";
  request.backend = assembly::BackendKind::kFake;
  request.simulation = &assembly::fake_simulation();
  request.domain = domain->config();
  request.rate_hz = 1000;
  auto assembled = assembly::assemble_hub(request, clock);
  if (!assembled) return state.SkipWithError(assembled.error().message.c_str());
  runtime::Hub& hub = *(*assembled)->hub;
  // The planner (and the in-process subscriber): a second participant in this process.
  auto participant = raw_participant(domain->domain_id());
  if (!participant) return state.SkipWithError(participant.error().message.c_str());
  {
    Subscriber subscriber;
    const std::string error =
        subscriber.start(state.range(0), *participant, *domain, "rt/dock_ecu/dock/state");
    if (!error.empty()) return state.SkipWithError(error.c_str());
    state.SetLabel(Subscriber::label(state.range(0)));
    Planner planner(*participant, changing);
    paced(state, [&] { hub.cycle(clock.now()); });
    state.counters["states_published"] = static_cast<double>(hub.nodes().front()->published());
  }
  dds_delete(*participant);
}

void BM_HubCycle_Repeating(benchmark::State& state) {
  hub_cycle(state, false);
}
void BM_HubCycle_Changing(benchmark::State& state) {
  hub_cycle(state, true);
}

// The DockState both write benchmarks write: a name, the echoed command and 4 slots.
struct BenchDockState {
  std::array<hub_msgs_msg_dds__DockSlot_, 4> slots{};
  hub_msgs_msg_dds__DockState_ sample{};
  BenchDockState() {
    for (auto& slot : slots) hubrt::msgs::typed::assign(slot.name, "smart_tool");
    hubrt::msgs::typed::assign(sample.name, "dock");
    hubrt::msgs::typed::assign(sample.echo.target_type, "dock");
    hubrt::msgs::typed::assign(sample.echo.target_name, "dock");
    hubrt::msgs::typed::assign(sample.echo.action, "monitor");
    sample.slots._buffer = slots.data();
    sample.slots._length = sample.slots._maximum = 4;
  }
  BenchDockState(const BenchDockState&) = delete;
  BenchDockState& operator=(const BenchDockState&) = delete;
};

void BM_PooledStateWrite(benchmark::State& state) {
  auto domain = test_support::TestDomain::acquire();
  if (!domain) return state.SkipWithError(domain.error().message.c_str());
  auto participant = dds::Participant::create(domain->config(), "bench_pooled_writer");
  if (!participant) return state.SkipWithError(participant.error().message.c_str());
  auto topic = dds::Topic<hub_msgs_msg_dds__DockState_>::create(*participant, "/bench/state");
  if (!topic) return state.SkipWithError(topic.error().message.c_str());
  auto writer = dds::Writer<hub_msgs_msg_dds__DockState_>::create(*participant, *topic);
  if (!writer) return state.SkipWithError(writer.error().message.c_str());
  auto reader_participant = raw_participant(domain->domain_id());
  if (!reader_participant) return state.SkipWithError(reader_participant.error().message.c_str());
  {
    Subscriber subscriber;
    const std::string error =
        subscriber.start(state.range(0), *reader_participant, *domain, "rt/bench/state");
    if (!error.empty()) return state.SkipWithError(error.c_str());
    if (state.range(0) != Subscriber::kNone && !writer->wait_for_readers(1, std::chrono::seconds(10)))
      return state.SkipWithError("no matched reader");
    state.SetLabel(Subscriber::label(state.range(0)));
    BenchDockState dock;
    paced(state, [&] {
      dock.sample.header.seq++;
      writer->write(dock.sample).ignore();
    });
    state.counters["pool_blocks"] = static_cast<double>(writer->pooled_blocks());
  }
  dds_delete(*reader_participant);
}

void BM_RawStateWrite(benchmark::State& state) {
  auto domain = test_support::TestDomain::acquire();
  if (!domain) return state.SkipWithError(domain.error().message.c_str());
  const auto config = domain->config();
  const dds_entity_t cyclone_domain = dds_create_domain(config.domain_id, config.cyclone_xml.c_str());
  auto writer_participant = raw_participant(config.domain_id);
  auto reader_participant = raw_participant(config.domain_id);
  if (!writer_participant || !reader_participant) return state.SkipWithError("cannot create participants");
  auto writer = raw_writer(*writer_participant, hub_msgs_msg_dds__DockState__desc, "rt/bench/state");
  if (!writer) return state.SkipWithError(writer.error().message.c_str());
  {
    Subscriber subscriber;
    const std::string error =
        subscriber.start(state.range(0), *reader_participant, *domain, "rt/bench/state");
    if (!error.empty()) return state.SkipWithError(error.c_str());
    if (state.range(0) != Subscriber::kNone && !wait_for_readers(*writer, 1, 10))
      return state.SkipWithError("no matched reader");
    state.SetLabel(Subscriber::label(state.range(0)));
    BenchDockState dock;
    hub_msgs_msg_dds__DockState_& sample = dock.sample;
    // As hubrt's Writer does: the keyless topic's one instance registered up front, so that Cyclone
    // does not create and collect it on every write.
    dds_instance_handle_t instance = 0;
    dds_register_instance(*writer, &instance, &sample);
    paced(state, [&] {
      sample.header.seq++;
      dds_write(*writer, &sample);
    });
  }
  dds_delete(*writer_participant);
  dds_delete(*reader_participant);
  dds_delete(cyclone_domain);
}

constexpr std::int64_t kIterations = 5000;  // 5 s at 1 kHz

BENCHMARK(BM_RawStateWrite)
    ->DenseRange(0, 2)
    ->Iterations(kIterations)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PooledStateWrite)
    ->DenseRange(0, 2)
    ->Iterations(kIterations)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_HubCycle_Repeating)
    ->DenseRange(0, 2)
    ->Iterations(kIterations)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_HubCycle_Changing)
    ->DenseRange(0, 2)
    ->Iterations(kIterations)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace hubrt::bench

int main(int argc, char** argv) {
  // Before any thread starts: the planner's allocations are told apart from the rest.
  hubrt::testing::count_allocations_of_threads_named({hubrt::bench::kPlannerThread});
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
