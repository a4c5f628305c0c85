// A hubd under test, with what every process test of a hub needs around it: the hub process on a
// board in the test's own DDS domain (TestDomain, loopback), the test's DDS participant (the
// planner, the other hubs, the world), a planner that repeats commands on a thread, streams of
// States, writers of /sim/input and /sim/fault, and waits for conditions with generous bounds
// whose failures say what was awaited and what hubd printed.
//
// Use it as a member of the test fixture: open() in SetUp, make the topics (the fixture owns the
// writers and streams and hands out pointers: they must go after its planner and before its
// participant), start() the hub.
//
//   ASSERT_NO_FATAL_FAILURE(hub_.open());
//   ASSERT_NO_FATAL_FAILURE(hub_.make_writer(commands_, "/dock/command"));
//   ASSERT_NO_FATAL_FAILURE(hub_.make_stream(states_, "/dock_ecu/dock/state"));
//   ASSERT_NO_FATAL_FAILURE(hub_.start({.hub = "dock_ecu"}));
//   hub_.plan(*commands_, command);  // every 50 ms until stop_planner()
//   ASSERT_TRUE(hub_.wait_for(*states_, [](const DockState& s) { return s.fresh_msg; }, "fresh"));
//
// Thread-safety: one test thread; the planner runs on its own thread and only calls what plan()
// was given.
#pragma once

#include <atomic>
#include <chrono>
#include <csignal>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/dds/participant.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/test_support/hub_process.h"
#include "hubrt/test_support/test_domain.h"

namespace hubrt::test_support {

// Generous: sanitizer builds on a busy 2-core machine running other builds and tests in
// parallel. The process tests check behaviour, not timing; the benchmarks measure timing.
inline constexpr Duration kPatience = std::chrono::seconds(15);

// The States (or any samples) of one topic, taken one at a time; the last taken stays readable.
template <class T>
class StateStream {
 public:
  StateStream(dds::Topic<T> topic, dds::Reader<T> reader)
      : topic_(std::move(topic)), reader_(std::move(reader)) {}

  // Takes samples until `predicate` holds for one (then latest()); false when none did within
  // `timeout`. Between takes it waits on the reader's data, not on a clock.
  bool take_until(const std::function<bool(const T&)>& predicate, Duration timeout = kPatience) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (auto now = std::chrono::steady_clock::now(); now < deadline;
         now = std::chrono::steady_clock::now()) {
      const Result<bool> taken = reader_.take_next(sample_);
      if (taken.is_ok() && taken.value()) {
        ++taken_;
        if (predicate(sample_.get())) return true;
        continue;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return false;
  }
  // The next sample, whatever it holds.
  bool take_any(Duration timeout = kPatience) {
    return take_until([](const T&) { return true; }, timeout);
  }

  [[nodiscard]] const T& latest() const { return sample_.get(); }
  [[nodiscard]] std::uint64_t taken() const { return taken_; }  // samples taken so far
  dds::Reader<T>& reader() { return reader_; }

 private:
  dds::Topic<T> topic_;
  dds::Reader<T> reader_;
  dds::Sample<T> sample_;
  std::uint64_t taken_ = 0;
};

class HubUnderTest {
  template <class T>
  struct WriterSlot {
    WriterSlot(dds::Topic<T> t, dds::Writer<T> w) : topic(std::move(t)), writer(std::move(w)) {}
    dds::Topic<T> topic;
    dds::Writer<T> writer;  // goes first
  };

 public:
  // `patience`: how long every wait of the fixture (start, matching, wait_for) may take before it
  // fails; more than kPatience for a hub whose work itself takes seconds.
  explicit HubUnderTest(Duration patience = kPatience) : patience_(patience) {}
  ~HubUnderTest();
  HubUnderTest(const HubUnderTest&) = delete;
  HubUnderTest& operator=(const HubUnderTest&) = delete;

  // Takes a DDS domain of the test's own and creates the test's participant. Call first, in SetUp
  // under ASSERT_NO_FATAL_FAILURE (it fails the test when either cannot be had).
  void open(const std::string& participant_name = "test-planner");

  // Starts hubd with `options` (board, hub, arguments, environment) in the domain and waits until
  // it runs; then, for each writer and stream made so far, until hubd has matched it (so that the
  // first command is not lost and the first State is on its way). A fatal failure with hubd's
  // output when it does not start.
  void start(HubProcessOptions options);
  // Starts hubd without waiting for any topic to match (a hub that is expected to refuse work).
  void start_unmatched(HubProcessOptions options);

  // A writer of T on `topic` (ROS name), owned by the fixture (it goes before the participant, after
  // the planner); `out` points at it. start() waits until hubd reads it.
  template <class T>
  void make_writer(dds::Writer<T>*& out, std::string_view topic,
                   const dds::Qos& qos = dds::Qos::ros2_default()) {
    auto t = dds::Topic<T>::create(participant(), topic);
    ASSERT_TRUE(t) << topic << ": " << t.error().message;
    auto writer = dds::Writer<T>::create(participant(), *t, qos);
    ASSERT_TRUE(writer) << topic << ": " << writer.error().message;
    auto slot = std::make_shared<WriterSlot<T>>(std::move(*t), std::move(*writer));
    out = &slot->writer;
    keep(slot);
    waits_.push_back([w = out, name = std::string(topic)](Duration timeout) {
      return w->wait_for_readers(1, timeout) ? std::string() : "no reader of " + name;
    });
  }
  // A stream of the States (or any samples) of T on `topic`, owned by the fixture; `out` points at
  // it. start() waits until hubd writes it.
  template <class T>
  void make_stream(StateStream<T>*& out, std::string_view topic,
                   const dds::Qos& qos = dds::Qos::ros2_default()) {
    auto t = dds::Topic<T>::create(participant(), topic);
    ASSERT_TRUE(t) << topic << ": " << t.error().message;
    auto reader = dds::Reader<T>::create(participant(), *t, qos);
    ASSERT_TRUE(reader) << topic << ": " << reader.error().message;
    auto stream = std::make_shared<StateStream<T>>(std::move(*t), std::move(*reader));
    out = stream.get();
    keep(stream);
    waits_.push_back([s = out, name = std::string(topic)](Duration timeout) {
      return s->reader().wait_for_writers(1, timeout) ? std::string() : "no writer of " + name;
    });
  }

  // Takes States from `stream` until `predicate` holds; on failure the result says what was
  // awaited (`what`), within how long, and what hubd printed.
  template <class T>
  ::testing::AssertionResult wait_for(StateStream<T>& stream,
                                      const std::type_identity_t<std::function<bool(const T&)>>& predicate,
                                      std::string_view what, std::optional<Duration> timeout = std::nullopt) {
    const Duration bound = timeout.value_or(patience_);
    if (stream.take_until(predicate, bound)) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << failure(what, bound, stream.taken());
  }

  // The planner: calls `write_once` every `period` on a thread of its own until stop_planner() (or
  // the end of the test); a second call replaces what it writes. `write_once` must be callable
  // from that thread while the test runs (capture values, not the test's locals by reference).
  void plan(std::function<void()> write_once, Duration period = std::chrono::milliseconds(50));
  // The same, writing a copy of `command` with `writer` (a planner repeats the wanted command).
  // Every write must succeed: stop_planner() fails the test, counting those that did not.
  template <class T>
  void plan(dds::Writer<T>& writer, const T& command, Duration period = std::chrono::milliseconds(50)) {
    plan(
        [this, &writer, command] {
          if (!writer.write(command).is_ok()) ++failed_writes_;
        },
        period);
  }
  // The planner goes quiet (the thread ends); plan() starts it again.
  void stop_planner();

  // The simulated world (hubs on the fake backend): /sim/input and /sim/fault, the writers made and
  // matched with hubd at the first use.
  void sim_input(const std::string& hub, const std::string& signal, bool active);
  void sim_fault(const std::string& hub, const std::string& device, const std::string& fault,
                 std::uint32_t value = 0);

  // The shipped hubs/<hub>/<hub>.yaml with `layout: node_type` made `layout: <layout>` and each
  // of `edits` (literal, each must be found) applied, as a file of the test's that goes with the
  // fixture. Its path, for HubProcessOptions::hub.
  std::string hub_file(const std::string& hub, const std::string& layout,
                       const std::vector<std::pair<std::string, std::string>>& edits = {});

  // Ends hubd now (killed and reaped, if it still runs), for a test whose devices must outlive it.
  void end_hub() { hub_.reset(); }

  // Sends `signal` and checks the documented clean stop: exit 0 and the outputs driven to their
  // safe state, in time.
  ::testing::AssertionResult stops_cleanly(int signal = SIGTERM);

  TestDomain& domain() { return *domain_; }
  dds::Participant& participant() { return *participant_; }
  HubProcess& hub() { return *hub_; }
  [[nodiscard]] bool running() const { return hub_.has_value(); }
  // hubd's output so far ("" before start), for failure messages.
  [[nodiscard]] std::string output() const { return hub_ ? hub_->output() : std::string(); }
  [[nodiscard]] Duration patience() const { return patience_; }

 private:
  void keep(std::shared_ptr<void> thing) { kept_.push_back(std::move(thing)); }
  std::string failure(std::string_view what, Duration timeout, std::uint64_t taken) const;

  Duration patience_;
  std::optional<TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::deque<std::shared_ptr<void>> kept_;  // writers and streams (with their topics), released last first
  std::vector<std::function<std::string(Duration)>> waits_;  // what start() waits to be matched
  std::optional<HubProcess> hub_;
  std::vector<std::string> files_;  // hub_file() copies, removed at the end

  std::mutex planner_mutex_;  // guards write_once_ and planning_, shared with the planner thread
  std::function<void()> write_once_;
  Duration period_{};
  bool planning_ = false;
  std::thread planner_;
  std::atomic<int> failed_writes_{0};

  struct SimWriters;
  std::shared_ptr<SimWriters> sim_;
};

}  // namespace hubrt::test_support
