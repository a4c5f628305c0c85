// Oversize commands cost a hub nothing (issue 11 point 1): a real hubd (Dock ECU on the simulated
// board) and an attacker that writes Dock commands with 1, 16 and 64 MB strings through a raw
// Cyclone writer whose type has no bounds (as any peer on the domain could, whatever our IDL
// says). Cyclone drops them on their first datagram (Internal/MaxSampleSize, set by hubd:
// dds/domain.h), so hubd's RSS stays where it was, the State heartbeat goes on, /diagnostics
// counts every one of them, and a normal command afterwards takes effect. Before the bound one
// 16 MB command cost hubd ~19 MB of RSS for good.
//
// The default suite sends 100 x 1 MB, 10 x 16 MB and 3 x 64 MB (HUBRT_OVERSIZE_FULL unset): ~8 s
// in all with ASan here, 1-2 s of it sending. The full 100/100/100 (a 64 MB sample is
// ~50,000 fragments of Cyclone's 1344 B FragmentSize in ~4,600 datagrams of 14720 B to read and
// drop) took 25-50 s of sending on this loaded machine: it is the `slow` twin of this binary,
// hubrt_oversize_command_full_test, outside the default suite.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/assembly/diagnostics_stage.h"
#include "hubrt/base/sanitizers.h"
#include "hubrt/dds/domain.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/test_support/hub_process.h"

#include "dock_messages.h"

namespace hubrt::integration {
using test_support::HubProcess;
using test_support::HubProcessOptions;
namespace {

using dock_ecu::DockState;
using std::chrono::milliseconds;
using std::chrono::seconds;
using DiagnosticArray = diagnostic_msgs_msg_dds__DiagnosticArray_;

#ifdef HUBRT_OVERSIZE_FULL
constexpr int kCount1MB = 100;
constexpr int kCount16MB = 100;
constexpr int kCount64MB = 100;
#else
constexpr int kCount1MB = 100;
constexpr int kCount16MB = 10;
constexpr int kCount64MB = 3;
#endif

constexpr std::size_t kMiB = 1024 * 1024;
// Generous: a busy 2-core machine running sanitizer builds of several engineers at once.
constexpr auto kPatience = seconds(20);
constexpr double kPeriodS = 0.1;  // dock_ecu.yaml: rate_hz 10
// The heartbeat may not stop: no two consecutive States further apart than two periods plus
// 300 ms for a loaded machine (the cycle thread may be woken late, ASan slows everything).
constexpr double kMaxGapS = 2 * kPeriodS + 0.3;
// RSS may move by less than 1 MB (issue 11): the receive buffers and malloc arenas are warm.
// Measured: a release hubd +4 kB through the full 300 commands, an ASan hubd +0.2 MB through the
// default 113; before the bound +155 MB (release, 16 -> 172 MB; ASan +69 MB). Only an ASan hubd through the
// full 300 moves more, +1.9 MB (ASan's own allocator: its size-class regions grow with the
// receive threads' malloc/free traffic where glibc reuses the same memory): 4 MB there.
#if defined(HUBRT_SANITIZE_ADDRESS) && defined(HUBRT_OVERSIZE_FULL)
constexpr long kMaxRssGrowthKb = 4096;
#else
constexpr long kMaxRssGrowthKb = 1024;
#endif

// The Dock command as an attacker would declare it: the same type name, unbounded strings, no
// type information (so Cyclone matches it by name, XTypes 7.6.3.4.2; Cyclone 0.10.2
// q_qosmatch.c, qos_match_mask_p). Its serialiser accepts strings of any length.
struct RawDockCommand {
  char* target_type;
  char* target_name;
  char* action;
};
// An unbounded string member (DDS_OP_ADR | DDS_OP_TYPE_STR, as idlc writes it; the enums are
// combined as integers, which C++20 wants spelled out).
constexpr std::uint32_t kAdrString =
    static_cast<std::uint32_t>(DDS_OP_ADR) | static_cast<std::uint32_t>(DDS_OP_TYPE_STR);
const std::uint32_t kRawDockCommandOps[] = {kAdrString,
                                            offsetof(RawDockCommand, target_type),
                                            kAdrString,
                                            offsetof(RawDockCommand, target_name),
                                            kAdrString,
                                            offsetof(RawDockCommand, action),
                                            static_cast<std::uint32_t>(DDS_OP_RTS)};
const dds_topic_descriptor_t kRawDockCommandDesc = {.m_size = sizeof(RawDockCommand),
                                                    .m_align = alignof(RawDockCommand),
                                                    .m_flagset = 0,
                                                    .m_nkeys = 0,
                                                    .m_typename = "hub_msgs::msg::dds_::DockCommand_",
                                                    .m_keys = nullptr,
                                                    .m_nops = 4,
                                                    .m_ops = kRawDockCommandOps,
                                                    .m_meta = "",
                                                    .type_information = {.data = nullptr, .sz = 0},
                                                    .type_mapping = {.data = nullptr, .sz = 0},
                                                    .restrict_data_representation = 0};

// The attacker's own process has no bound on what it writes (later sources override earlier
// ones in Cyclone's configuration: ddsi_config.c, do_update).
constexpr const char* kUnboundedXml =
    "<CycloneDDS><Domain id=\"any\"><Internal><MaxSampleSize>2147483647 B</MaxSampleSize>"
    "</Internal></Domain></CycloneDDS>";

long rss_kb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  }
  return -1;
}

std::optional<std::uint64_t> oversize_count(const DiagnosticArray& a) {
  for (std::uint32_t i = 0; i < a.status._length; ++i) {
    const auto& s = a.status._buffer[i];
    for (std::uint32_t k = 0; k < s.values._length; ++k) {
      if (s.values._buffer[k].key != nullptr &&
          std::string(s.values._buffer[k].key) == "oversize_samples_dropped")
        return std::stoull(s.values._buffer[k].value);
    }
  }
  return std::nullopt;
}

class OversizeCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    dds::DomainConfig config = domain_->config();
    config.cyclone_xml += std::string(",") + kUnboundedXml;
    auto participant = dds::Participant::create(config, "test-attacker");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));

    auto state_topic = dds::Topic<DockState>::create(*participant_, "/dock_ecu/dock/state");
    ASSERT_TRUE(state_topic) << state_topic.error().message;
    state_topic_.emplace(std::move(*state_topic));
    auto states = dds::Reader<DockState>::create(*participant_, *state_topic_);
    ASSERT_TRUE(states) << states.error().message;
    states_.emplace(std::move(*states));
    auto diag_topic = dds::Topic<DiagnosticArray>::create(*participant_, "/diagnostics");
    ASSERT_TRUE(diag_topic) << diag_topic.error().message;
    diag_topic_.emplace(std::move(*diag_topic));
    auto diagnostics = dds::Reader<DiagnosticArray>::create(*participant_, *diag_topic_);
    ASSERT_TRUE(diagnostics) << diagnostics.error().message;
    diagnostics_.emplace(std::move(*diagnostics));

    // The raw writer: reliable, every sample kept until acknowledged (so each one reaches the
    // hub at least in part and is counted there), writes may wait for that.
    topic_ =
        dds_create_topic(participant_->handle(), &kRawDockCommandDesc, "rt/dock/command", nullptr, nullptr);
    ASSERT_GT(topic_, 0) << dds_strretcode(topic_);
    dds_qos_t* qos = dds_create_qos();
    const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
    dds_qset_data_representation(qos, 1, &xcdr1);
    dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(60));
    dds_qset_history(qos, DDS_HISTORY_KEEP_ALL, 0);
    writer_ = dds_create_writer(participant_->handle(), topic_, qos, nullptr);
    dds_delete_qos(qos);
    ASSERT_GT(writer_, 0) << dds_strretcode(writer_);

    HubProcessOptions options;
    options.hub = "dock_ecu";
    // Under AddressSanitizer freed memory stays resident in its quarantine (256 MB by default)
    // instead of being reused: RSS would then measure ASan, not hubd. Without it an ASan hubd
    // is as flat as a release one here. No effect on builds without ASan.
    // NOLINTNEXTLINE(concurrency-mt-unsafe): no other thread runs yet.
    const char* asan = std::getenv("ASAN_OPTIONS");
    options.extra_env = {
        {"ASAN_OPTIONS", std::string(asan == nullptr ? "" : asan) + ":quarantine_size_mb=0"}};
    auto hub = HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(states_->wait_for_writers(1, kPatience)) << hub_->output();
    ASSERT_TRUE(wait_for_command_reader()) << hub_->output();
    watcher_ = std::thread([this] { watch_states(); });
  }

  void TearDown() override {
    watching_ = false;
    if (watcher_.joinable()) watcher_.join();
    if (writer_ > 0) (void)dds_delete(writer_);
    if (topic_ > 0) (void)dds_delete(topic_);
  }

  bool wait_for_command_reader() const {
    const auto end = std::chrono::steady_clock::now() + kPatience;
    while (std::chrono::steady_clock::now() < end) {
      dds_publication_matched_status_t status{};
      if (dds_get_publication_matched_status(writer_, &status) == DDS_RETCODE_OK && status.current_count > 0)
        return true;
      std::this_thread::sleep_for(milliseconds(20));
    }
    return false;
  }

  // Takes every State as it comes, keeping the hub's stamp per sequence number, and the last one.
  void watch_states() {
    dds::Sample<DockState> sample;
    while (watching_) {
      const Result<bool> taken = states_->take_next(sample);
      if (!taken.is_ok() || !taken.value()) {
        std::this_thread::sleep_for(milliseconds(2));
        continue;
      }
      const DockState& s = sample.get();
      const std::lock_guard lock(mutex_);
      stamps_[s.header.seq] = s.header.stamp.sec + s.header.stamp.nanosec * 1e-9;
      last_action_ = static_cast<const char*>(s.echo.action);
      last_fresh_ = s.fresh_msg;
    }
  }

  void write(const char* action) {
    RawDockCommand c{const_cast<char*>("dock"), const_cast<char*>("dock"),
                     const_cast<char*>(action)};  // NOLINT
    const dds_return_t rc = dds_write(writer_, &c);
    ASSERT_EQ(rc, DDS_RETCODE_OK) << dds_strretcode(rc);
  }

  // Writes `count` commands whose action is a string of `size` bytes.
  void write_oversize(std::size_t size, int count) {
    if (payload_.size() < size + 1) payload_.assign(size + 1, 'x');
    payload_[size] = '\0';
    for (int i = 0; i < count; ++i) write(payload_.data());
    payload_[size] = 'x';
  }

  // The latest oversize_samples_dropped on /diagnostics (published once a second).
  std::optional<std::uint64_t> latest_oversize_count(Duration wait) {
    std::optional<std::uint64_t> latest;
    dds::Sample<DiagnosticArray> diag;
    const auto end = std::chrono::steady_clock::now() + wait;
    while (std::chrono::steady_clock::now() < end) {
      const Result<bool> taken = diagnostics_->take_next(diag);
      if (!taken.is_ok() || !taken.value()) {
        std::this_thread::sleep_for(milliseconds(20));
        continue;
      }
      if (auto n = oversize_count(diag.get())) latest = n;
    }
    return latest;
  }

  // The longest time between two consecutive States (by sequence number) on the hub's clock.
  double worst_gap_s(std::uint64_t* states) {
    const std::lock_guard lock(mutex_);
    double worst = 0;
    for (auto it = stamps_.begin(); it != stamps_.end(); ++it) {
      const auto next = std::next(it);
      if (next == stamps_.end()) break;
      worst = std::max(worst, (next->second - it->second) / static_cast<double>(next->first - it->first));
      if (next->first != it->first + 1) worst = std::max(worst, next->second - it->second);
    }
    *states = stamps_.size();
    return worst;
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<DockState>> state_topic_;
  std::optional<dds::Reader<DockState>> states_;
  std::optional<dds::Topic<DiagnosticArray>> diag_topic_;
  std::optional<dds::Reader<DiagnosticArray>> diagnostics_;
  dds_entity_t topic_ = 0;
  dds_entity_t writer_ = 0;
  std::optional<HubProcess> hub_;
  std::string payload_;
  std::atomic<bool> watching_{true};
  std::thread watcher_;
  std::mutex mutex_;
  std::map<std::uint64_t, double> stamps_;
  std::string last_action_;
  bool last_fresh_ = false;
};

// The two binaries need distinct test names: ctest knows tests by name, and labels them by it.
#ifdef HUBRT_OVERSIZE_FULL
using OversizeCommandFullTest = OversizeCommandTest;
#define HUBRT_OVERSIZE_SUITE OversizeCommandFullTest
#else
#define HUBRT_OVERSIZE_SUITE OversizeCommandTest
#endif

TEST_F(HUBRT_OVERSIZE_SUITE, CostNoMemoryStopNoHeartbeatAndAreCountedInDiagnostics) {
  const pid_t pid = hub_->process().pid();
  // Warm-up: the paths the oversize commands take (receive buffers, the discard warning), a
  // normal command, and a few seconds of running.
  write_oversize(kMiB, 3);
  write("monitor");
  ASSERT_EQ(dds_wait_for_acks(writer_, DDS_SECS(60)), DDS_RETCODE_OK);
  const std::optional<std::uint64_t> count_before = latest_oversize_count(seconds(3));
  const long rss_before = rss_kb(pid);
  ASSERT_GT(rss_before, 0);

  const auto start = std::chrono::steady_clock::now();
  write_oversize(kMiB, kCount1MB);
  std::printf("hubd RSS after %d x 1 MB: %ld kB\n", kCount1MB, rss_kb(pid));
  write_oversize(16 * kMiB, kCount16MB);
  std::printf("hubd RSS after %d x 16 MB: %ld kB\n", kCount16MB, rss_kb(pid));
  write_oversize(64 * kMiB, kCount64MB);
  std::printf("hubd RSS after %d x 64 MB: %ld kB\n", kCount64MB, rss_kb(pid));
  ASSERT_EQ(dds_wait_for_acks(writer_, DDS_SECS(120)), DDS_RETCODE_OK);
  const double sending_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  payload_ = std::string();  // the test's own 64 MB, not to be confused with the hub's

  const std::optional<std::uint64_t> count_after = latest_oversize_count(seconds(3));
  const long rss_after = rss_kb(pid);
  std::uint64_t states = 0;
  const double worst_gap = worst_gap_s(&states);
  const int sent = kCount1MB + kCount16MB + kCount64MB;
  std::printf(
      "%d oversize commands (%d x 1 MB, %d x 16 MB, %d x 64 MB) in %.1f s; hubd RSS %ld -> %ld kB; "
      "%llu States, worst gap %.3f s; oversize_samples_dropped %llu -> %llu\n",
      sent, kCount1MB, kCount16MB, kCount64MB, sending_s, rss_before, rss_after,
      static_cast<unsigned long long>(states), worst_gap,
      static_cast<unsigned long long>(count_before.value_or(0)),
      static_cast<unsigned long long>(count_after.value_or(0)));

  // Under an emulator (the cross tier's qemu-user) the RSS read is the emulator's, translation
  // cache included, and its speed is not the board's: memory and heartbeat are judged in native
  // builds; the count and the command afterwards hold everywhere.
  if (test_support::target_emulator().empty()) {
    EXPECT_LE(rss_after - rss_before, kMaxRssGrowthKb) << "hubd kept the oversize commands' memory";
    // The States cover the whole run: the heartbeat went on while the commands came in.
    EXPECT_GE(static_cast<double>(states), sending_s / kPeriodS / 2) << "too few States\n" << hub_->output();
    EXPECT_LE(worst_gap, kMaxGapS) << "the heartbeat stopped";
  } else {
    std::printf("under an emulator: RSS and heartbeat gap printed above, not judged\n");
  }
  // Cyclone warns once per dropped sample (q_receive.c, drop_oversize), and every sample of a
  // keep-all reliable writer reaches the hub at least in part: exactly the number sent.
  EXPECT_TRUE(count_before && count_after) << "no oversize_samples_dropped on /diagnostics";
  if (count_before && count_after) {
    EXPECT_EQ(*count_after - *count_before, static_cast<std::uint64_t>(sent));
  }

  // A normal command still takes effect.
  write("reset");
  bool echoed = false;
  const auto end = std::chrono::steady_clock::now() + kPatience;
  while (!echoed && std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(milliseconds(20));
    const std::lock_guard lock(mutex_);
    echoed = last_action_ == "reset" && last_fresh_;
  }
  EXPECT_TRUE(echoed) << "a normal command after the oversize ones was not echoed\n" << hub_->output();
}

}  // namespace
}  // namespace hubrt::integration
