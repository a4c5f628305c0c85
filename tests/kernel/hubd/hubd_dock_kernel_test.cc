// hubd running the Dock ECU on the linux backend in the kernel tier's guest. Its four slot sensors
// are lines of a gpio-sim chip, driven through the simulator's pull files as docked tools would
// drive them, while a planner-side client in the same guest commands the hub and reads its State
// over Cyclone DDS on loopback, in a domain of its own. Skips outside the tier (tests/kernel/run).
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gpiod.h>
#include <gtest/gtest.h>

#include "hubrt/dds/qos.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/kernel_test/environment.h"
#include "hubrt/kernel_test/gpio_sim.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/test_support/hub_under_test.h"

#include "dock_board_file.h"
#include "dock_messages.h"

namespace hubrt::kernel_test {
namespace {

using dock_ecu::DockCommand;
using dock_ecu::DockState;
using std::chrono::microseconds;
using std::chrono::milliseconds;
using std::chrono::seconds;
using std::chrono::steady_clock;
using test_support::HubProcessOptions;

// Generous: the guest runs under software emulation (TCG) on a 2-core host that may be busy with
// sanitizer builds; hubd then takes seconds to start and a scheduling hiccup can take a second.
// It also covers the supervised devices' back-off (at most 2 s) when a line comes back. These tests check
// behaviour, not timing.
constexpr auto kPatience = seconds(30);

constexpr std::size_t kSmartTool = 2;  // index into kDockSlots and the State's slots
constexpr std::size_t kSpare = 3;

std::int64_t wall_ns() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

// The State's stamp: the wall time the hub read at the start of the cycle that built it, before
// it read its lines.
std::int64_t stamp_ns(const DockState& s) {
  return static_cast<std::int64_t>(s.header.stamp.sec) * 1'000'000'000 + s.header.stamp.nanosec;
}

std::string error_list(const DockState& s) {
  std::string out;
  for (std::uint32_t i = 0; i < s.error_list._length; ++i) out += std::string(s.error_list._buffer[i]) + "; ";
  return out;
}

bool has_error(const DockState& s, const std::string& part) {
  return error_list(s).find(part) != std::string::npos;
}

// One bit per slot in kDockSlots order; nullopt unless the State lists exactly those slots.
std::optional<unsigned> occupancy(const DockState& s) {
  if (s.slots._length != kDockSlots.size()) return std::nullopt;
  unsigned bits = 0;
  for (std::size_t i = 0; i < kDockSlots.size(); ++i) {
    if (std::string(s.slots._buffer[i].name) != kDockSlots[i].slot) return std::nullopt;
    if (s.slots._buffer[i].occupied) bits |= 1U << i;
  }
  return bits;
}

std::string describe(const DockState& s) {
  std::string slots;
  for (std::uint32_t i = 0; i < s.slots._length; ++i) {
    slots += fmt::format(" {}={}", s.slots._buffer[i].name, s.slots._buffer[i].occupied ? 1 : 0);
  }
  return fmt::format("last State: seq {}, slots [{} ], fresh_msg {}, echo '{}', errors [{}]", s.header.seq,
                     slots, s.fresh_msg, std::string(s.echo.action), error_list(s));
}

// A line requested by "another program" (this test, under another consumer name), released on
// destruction: closing the chip releases its requested lines.
using HeldChip = std::unique_ptr<gpiod_chip, decltype(&gpiod_chip_close)>;

class HubdDockKernelTest : public ::testing::Test {
 protected:
  void SetUp() override {
    HUBRT_SKIP_OUTSIDE_KERNEL_TIER();
    auto chip = gpiosim_chip_from_env();
    ASSERT_TRUE(chip) << "the tier set HUBRT_KERNEL_TIER but not every HUBRT_GPIOSIM_* variable";
    chip_ = *chip;
    // Tests of this program share the chip: every one starts with no tool docked.
    for (std::size_t slot = 0; slot < kDockSlots.size(); ++slot) pull(chip_, slot, Pull::kDown);
    ASSERT_NO_FATAL_FAILURE(hub_.open("kernel-test-planner"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_writer(command_writer_, "/dock/command"));
    // Keep every State: the debounce test must see each one, at 100 per second.
    ASSERT_NO_FATAL_FAILURE(
        hub_.make_stream(states_, "/dock_ecu/dock/state", dds::Qos::ros2_default().keep_all()));
  }

  // Writes a board file for `chip` (into TMPDIR: the guest's root is read-only) and starts hubd
  // on it with the linux backend.
  void start_hub(const GpioSimChip& chip, ChipReference how,
                 const std::vector<std::string>& extra_args = {}) {
    auto board = DockBoardFile::write(chip, how, std::filesystem::temp_directory_path().string());
    ASSERT_TRUE(board) << board.error().message;
    board_.emplace(std::move(*board));
    HubProcessOptions options;
    options.board = board_->path();
    options.hub = "dock_ecu";
    options.extra_args = {"--backend", "linux"};
    options.start_patience = kernel_test::kHubdStartPatience;
    options.extra_args.insert(options.extra_args.end(), extra_args.begin(), extra_args.end());
    const auto began = steady_clock::now();
    ASSERT_NO_FATAL_FAILURE(hub_.start(options)) << "board file " << board_->path() << ":\n"
                                                 << board_->text();
    // In every run's log: how near a start comes to kHubdStartPatience (a fresh guest's first hubd reads
    // its program and libraries through 9p for the first time).
    std::printf("hubd started and matched in %.1f s\n",
                std::chrono::duration<double>(steady_clock::now() - began).count());
  }

  // Takes the next State into state_; false if none comes within `timeout`.
  bool next_state(Duration timeout) {
    const auto deadline = steady_clock::now() + timeout;
    do {
      const Result<bool> taken = states_->reader().take_next(state_);
      if (taken.is_ok() && taken.value()) return true;
      std::this_thread::sleep_for(milliseconds(1));
    } while (steady_clock::now() < deadline);
    return false;
  }

  // Takes States until one satisfies `predicate`; false after `timeout`.
  bool wait_for_state(const std::function<bool(const DockState&)>& predicate, Duration timeout = kPatience) {
    const auto deadline = steady_clock::now() + timeout;
    while (steady_clock::now() < deadline) {
      if (next_state(milliseconds(100)) && predicate(state_.get())) return true;
    }
    return false;
  }

  bool wait_for_occupancy(unsigned bits) {
    return wait_for_state([bits](const DockState& s) { return occupancy(s) == bits; });
  }

  static void pull(const GpioSimChip& chip, std::size_t slot, Pull level) {
    auto done = set_pull(chip, kDockSlots[slot].offset, level);
    ASSERT_TRUE(done) << done.error().message;
  }

  void send(const char* action) {
    DockCommand command{};
    hubrt::msgs::typed::assign(command.target_type, "dock");
    hubrt::msgs::typed::assign(command.target_name, "dock");
    hubrt::msgs::typed::assign(command.action, action);
    ASSERT_TRUE(command_writer_->write(command).is_ok());
  }

  // For failure messages: the last State and what hubd printed.
  std::string context() const { return describe(state_.get()) + "\nhubd output:\n" + hub_.output(); }

  GpioSimChip chip_;
  dds::Writer<DockCommand>* command_writer_ = nullptr;
  test_support::StateStream<DockState>* states_ = nullptr;
  dds::Sample<DockState> state_;
  std::optional<DockBoardFile> board_;
  test_support::HubUnderTest hub_{kPatience};
};

TEST_F(HubdDockKernelTest, SlotsFollowThePullsOfTheirLines) {
  ASSERT_NO_FATAL_FAILURE(start_hub(chip_, ChipReference::kPath));
  ASSERT_TRUE(wait_for_state([](const DockState& s) {
    return occupancy(s) == 0U && s.error_list._length == 0;
  })) << context();
  for (std::size_t slot = 0; slot < kDockSlots.size(); ++slot) {
    pull(chip_, slot, Pull::kUp);
    EXPECT_TRUE(wait_for_occupancy(1U << slot)) << kDockSlots[slot].slot << " pulled up; " << context();
    pull(chip_, slot, Pull::kDown);
    EXPECT_TRUE(wait_for_occupancy(0)) << kDockSlots[slot].slot << " pulled down again; " << context();
  }
  // Every tool home: the station at rest.
  for (std::size_t slot = 0; slot < kDockSlots.size(); ++slot) pull(chip_, slot, Pull::kUp);
  EXPECT_TRUE(wait_for_occupancy(0b1111)) << context();
  EXPECT_EQ(state_.get().error_list._length, 0U) << error_list(state_.get());
}

TEST_F(HubdDockKernelTest, RequestsItsLinesWithTheBoardsPullDownBias) {
  // The world pulls every slot line up before hubd runs...
  for (std::size_t slot = 0; slot < kDockSlots.size(); ++slot) pull(chip_, slot, Pull::kUp);
  ASSERT_NO_FATAL_FAILURE(start_hub(chip_, ChipReference::kPath));
  // ...but hubd requests them with the board's pull-down bias, which gpio-sim applies as the
  // line's pull: from its first State on, hubd reads them low (without the bias: all occupied).
  ASSERT_TRUE(next_state(kPatience)) << context();
  EXPECT_EQ(occupancy(state_.get()), 0U) << context();
  for (const DockSlotWiring& slot : kDockSlots) {
    auto value = read_value(chip_, slot.offset);
    ASSERT_TRUE(value) << value.error().message;
    EXPECT_EQ(*value, 0) << slot.signal << " on line " << slot.offset;
  }
}

// The debounce test's view of one short pulse on a slot line.
struct PulseOutcome {
  std::int64_t length_ns = 0;   // from before the rising write to after the falling one: >= the pulse
  std::int64_t max_gap_ns = 0;  // between the stamps of consecutive States around it
  bool lost = false;            // a State went missing (sequence gap)
  bool looked = false;          // a cycle started inside it, so most likely read it high
  bool showed = false;          // a State showed the slot occupied
};

TEST_F(HubdDockKernelTest, DebounceHidesPulsesShorterThanItsWindow) {
  // At 100 Hz the hub reads its lines every 10 ms, so it reads many of the short pulses below and,
  // without the 20 ms debounce, would report them.
  ASSERT_NO_FATAL_FAILURE(start_hub(chip_, ChipReference::kPath, {"--rate", "100"}));
  ASSERT_TRUE(wait_for_occupancy(0)) << context();
  constexpr auto kHold = milliseconds(2);
  constexpr std::int64_t kWindowNs = std::int64_t{kDockDebounceMs} * 1'000'000;
  // Which pulses prove something. The debouncer times each sample by the clock reading its cycle
  // started with, not by the read itself. A cycle held up for a while (a descheduled vCPU under
  // emulation) between the two therefore stamps its read too early, and two reads of one pulse
  // can look a window apart. For that, the cycle that first read the pulse high must have started
  // at least (window - pulse) before the next cycle started: so a pulse is judged only if no two
  // consecutive States around it are that far apart, none went missing, and it was short.
  const auto judged = [](const PulseOutcome& p) {
    return !p.lost && p.length_ns <= kWindowNs / 2 && p.max_gap_ns < kWindowNs - p.length_ns;
  };
  constexpr int kMaxPulses = 200;
  constexpr int kWantedSeen = 5;
  int pulses = 0;
  int judged_count = 0;
  int seen = 0;
  int shown_unjudged = 0;
  std::string reported;
  std::uint64_t last_seq = state_.get().header.seq;
  std::int64_t last_stamp = stamp_ns(state_.get());
  const auto budget = steady_clock::now() + seconds(60);
  for (; pulses < kMaxPulses && seen < kWantedSeen && steady_clock::now() < budget; ++pulses) {
    // Each pulse starts right after a State arrived, so on a fast guest it starts just after a
    // cycle and ends long before the next: no cycle falls inside it, ever (a run with 197 judged
    // pulses, 0 looked at). A delay walking through the 10 ms period in steps of 3.7 ms puts the
    // pulses at every phase of the cycle instead.
    std::this_thread::sleep_for(microseconds((pulses * 3700) % 10000));
    PulseOutcome pulse;
    const std::int64_t rise = wall_ns();
    pull(chip_, kSmartTool, Pull::kUp);
    std::this_thread::sleep_for(kHold);
    pull(chip_, kSmartTool, Pull::kDown);
    const std::int64_t fall = wall_ns();
    pulse.length_ns = fall - rise;
    // Every State up to the first one from a cycle that started after the pulse and shows the slot
    // empty: that cycle read the line low, and the debouncer's level is low with nothing pending
    // (after a long pulse that was rightly reported, the low must hold for the window first). So
    // every State taken here is about this pulse alone.
    bool settled = false;
    const auto deadline = steady_clock::now() + kPatience;
    while (!settled && steady_clock::now() < deadline) {
      if (!next_state(milliseconds(100))) continue;
      const DockState& s = state_.get();
      const std::int64_t stamp = stamp_ns(s);
      pulse.lost = pulse.lost || s.header.seq != last_seq + 1;
      pulse.max_gap_ns = std::max(pulse.max_gap_ns, stamp - last_stamp);
      pulse.showed = pulse.showed || occupancy(s).value_or(0) != 0;
      pulse.looked = pulse.looked || (stamp >= rise && stamp + 1'000'000 <= fall);
      last_seq = s.header.seq;
      last_stamp = stamp;
      settled = stamp > fall && occupancy(s) == 0U;
    }
    ASSERT_TRUE(settled) << "no State showing the slot empty after pulse " << pulses << "; " << context();
    if (!judged(pulse)) {
      if (pulse.showed) ++shown_unjudged;
      continue;
    }
    ++judged_count;
    if (pulse.looked) ++seen;
    if (pulse.showed) {
      reported += fmt::format(" pulse {} ({:.1f} ms, States {:.1f} ms apart at most);", pulses,
                              static_cast<double>(pulse.length_ns) / 1e6,
                              static_cast<double>(pulse.max_gap_ns) / 1e6);
    }
  }
  EXPECT_EQ(reported, "") << "pulses shorter than the debounce window were reported as a docked tool";
  // A hub that never read a line during a judged pulse proves nothing about the debounce.
  EXPECT_GE(seen, 1) << pulses << " pulses, " << judged_count << " judged, none had a cycle inside; "
                     << context();
  std::printf(
      "debounce: %d pulses, %d judged, %d of them with a cycle inside; %d unjudged ones shown as occupied\n",
      pulses, judged_count, seen, shown_unjudged);
  RecordProperty("pulses", pulses);
  RecordProperty("pulses_judged", judged_count);
  RecordProperty("pulses_judged_with_a_cycle_inside", seen);
  RecordProperty("pulses_unjudged_shown_occupied", shown_unjudged);
  // A level that holds is still reported.
  pull(chip_, kSmartTool, Pull::kUp);
  EXPECT_TRUE(wait_for_occupancy(1U << kSmartTool)) << context();
}

TEST_F(HubdDockKernelTest, EchoesCommandsAndDropsFreshMsgWhenTheyStop) {
  ASSERT_NO_FATAL_FAILURE(start_hub(chip_, ChipReference::kPath));
  ASSERT_TRUE(command_writer_->wait_for_readers(1, kPatience));
  ASSERT_TRUE(wait_for_state([](const DockState& s) { return !s.fresh_msg; }))
      << "not fresh before any command";
  // Like the planner: the same command, repeatedly.
  std::atomic<bool> sending{true};
  std::thread planner([&] {
    while (sending) {
      send("monitor");
      std::this_thread::sleep_for(milliseconds(50));
    }
  });
  const bool echoed = wait_for_state([](const DockState& s) {
    return s.fresh_msg && std::string(s.echo.action) == "monitor" &&
           std::string(s.echo.target_name) == "dock";
  });
  // The slots keep following their lines while commands flow.
  pull(chip_, kSpare, Pull::kUp);
  const bool followed =
      wait_for_state([](const DockState& s) { return s.fresh_msg && occupancy(s) == 1U << kSpare; });
  sending = false;
  planner.join();
  ASSERT_TRUE(echoed) << context();
  EXPECT_TRUE(followed) << context();
  EXPECT_EQ(state_.get().error_list._length, 0U) << error_list(state_.get());
  // The planner went quiet: after the 1 s command timeout fresh_msg turns false with an error.
  ASSERT_TRUE(wait_for_state([](const DockState& s) { return !s.fresh_msg; })) << context();
  EXPECT_TRUE(has_error(state_.get(), "command timeout")) << error_list(state_.get());
  EXPECT_STREQ(state_.get().echo.action, "monitor") << "the echo still shows the last command";
}

TEST_F(HubdDockKernelTest, ReportsARemovedChipAndRecoversWhenItComesBack) {
  // A chip of its own, referred to by label, so that it can go away and come back as another
  // gpiochipN, like a GPIO expander whose cable is pulled and plugged in again.
  const std::string label = fmt::format("hubrt-dock-{}", ::getpid());
  auto made = ScopedGpioSimChip::create(label, chip_.num_lines);
  ASSERT_TRUE(made) << made.error().message;
  std::optional<ScopedGpioSimChip> expander(std::move(*made));
  const GpioSimChip first = expander->chip();
  ASSERT_NO_FATAL_FAILURE(start_hub(first, ChipReference::kLabel));
  ASSERT_TRUE(wait_for_state([](const DockState& s) {
    return occupancy(s) == 0U && s.error_list._length == 0;
  })) << context();
  pull(first, kSmartTool, Pull::kUp);
  ASSERT_TRUE(wait_for_occupancy(1U << kSmartTool)) << context();

  expander.reset();  // removes the chip while hubd holds its lines
  const auto every_slot_reported = [](const DockState& s) {
    for (const DockSlotWiring& slot : kDockSlots) {
      if (!has_error(s, fmt::format("slot '{}'", slot.slot))) return false;
    }
    return true;
  };
  ASSERT_TRUE(wait_for_state(every_slot_reported)) << context();
  // Never claim a tool is home without seeing it.
  EXPECT_EQ(occupancy(state_.get()), 0U) << context();
  EXPECT_TRUE(has_error(state_.get(), "not available")) << error_list(state_.get());
  // hubd keeps running and publishing (it did not crash or stop on the error).
  const std::uint64_t seq = state_.get().header.seq;
  ASSERT_TRUE(wait_for_state([seq](const DockState& s) { return s.header.seq >= seq + 5; })) << context();
  EXPECT_TRUE(every_slot_reported(state_.get())) << context();

  auto remade = ScopedGpioSimChip::create(label, chip_.num_lines);
  ASSERT_TRUE(remade) << remade.error().message;
  expander.emplace(std::move(*remade));
  // Opened again on the next retry; the errors go away by themselves.
  ASSERT_TRUE(wait_for_state([](const DockState& s) {
    return occupancy(s) == 0U && s.error_list._length == 0;
  })) << context();
  pull(expander->chip(), kSmartTool, Pull::kUp);
  EXPECT_TRUE(wait_for_occupancy(1U << kSmartTool)) << context();

  ASSERT_TRUE(hub_.hub().process().signal(SIGTERM));
  auto status = hub_.hub().process().wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << hub_.output();
}

TEST_F(HubdDockKernelTest, ReportsALineHeldByAnotherProgramUntilItIsReleased) {
  // Another program holds the spare slot's line, as a stray gpioget or a second hubd would.
  HeldChip holder(gpiod_chip_open(chip_.dev_path.c_str()), &gpiod_chip_close);
  ASSERT_NE(holder, nullptr) << chip_.dev_path;
  gpiod_line* line = gpiod_chip_get_line(holder.get(), kDockSlots[kSpare].offset);
  ASSERT_NE(line, nullptr);
  ASSERT_EQ(gpiod_line_request_input(line, "kernel-test-holder"), 0);

  ASSERT_NO_FATAL_FAILURE(start_hub(chip_, ChipReference::kPath));
  ASSERT_TRUE(wait_for_state([](const DockState& s) { return has_error(s, "slot 'spare'"); })) << context();
  EXPECT_TRUE(has_error(state_.get(), "busy, held by 'kernel-test-holder'")) << error_list(state_.get());
  EXPECT_EQ(state_.get().error_list._length, 1U)
      << "only the spare slot is affected: " << error_list(state_.get());
  // The other slots work meanwhile.
  pull(chip_, 0, Pull::kUp);
  EXPECT_TRUE(wait_for_occupancy(1U)) << context();

  holder.reset();
  ASSERT_TRUE(wait_for_state([](const DockState& s) { return s.error_list._length == 0; })) << context();
  pull(chip_, kSpare, Pull::kUp);
  EXPECT_TRUE(wait_for_occupancy(1U | 1U << kSpare)) << context();
}

}  // namespace
}  // namespace hubrt::kernel_test
