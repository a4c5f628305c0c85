#include "hubrt/test_support/hub_under_test.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "hubrt/sim/sim_bridge_stage.h"

#include "sim.h"

namespace hubrt::test_support {

struct HubUnderTest::SimWriters {
  dds::Writer<hub_msgs_msg_dds__SimInput_>* input = nullptr;
  dds::Writer<hub_msgs_msg_dds__SimFault_>* fault = nullptr;
};

namespace {

char* wire(const std::string& text) {
  return const_cast<char*>(text.c_str());  // NOLINT: idlc's unbounded strings are char*, not written
}

// Waits until hubd reads `writer`, so that what is written next is not lost.
template <class T>
void match(const dds::Writer<T>& writer, std::string_view topic, Duration patience,
           const std::string& output) {
  ASSERT_TRUE(writer.wait_for_readers(1, patience)) << "hubd does not read " << topic << "\nhubd:\n"
                                                    << output;
}

}  // namespace

HubUnderTest::~HubUnderTest() {
  stop_planner();
  // The writers and readers before the participant (a writer whose participant went first aborts
  // in Cyclone's sertype release), the last made first.
  while (!kept_.empty()) kept_.pop_back();
  for (const std::string& file : files_) {
    std::error_code ignored;
    std::filesystem::remove_all(std::filesystem::path(file).parent_path(), ignored);
  }
}

void HubUnderTest::open(const std::string& participant_name) {
  auto domain = TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  domain_.emplace(std::move(*domain));
  auto participant = dds::Participant::create(domain_->config(), participant_name);
  ASSERT_TRUE(participant) << participant.error().message;
  participant_.emplace(std::move(*participant));
}

void HubUnderTest::start_unmatched(HubProcessOptions options) {
  ASSERT_TRUE(domain_.has_value()) << "HubUnderTest::open() first";
  options.start_patience = std::max(options.start_patience, patience_);
  auto hub = HubProcess::start(*domain_, options);
  ASSERT_TRUE(hub) << hub.error().message;
  hub_.emplace(std::move(*hub));
}

void HubUnderTest::start(HubProcessOptions options) {
  ASSERT_NO_FATAL_FAILURE(start_unmatched(std::move(options)));
  for (const auto& wait : waits_) {
    const std::string missing = wait(patience_);
    ASSERT_TRUE(missing.empty()) << missing << " within "
                                 << std::chrono::duration_cast<std::chrono::seconds>(patience_).count()
                                 << " s\nhubd:\n"
                                 << output();
  }
}

std::string HubUnderTest::failure(std::string_view what, Duration timeout, std::uint64_t taken) const {
  return fmt::format("no sample for which {} within {} s ({} samples taken so far)\nhubd:\n{}", what,
                     std::chrono::duration_cast<std::chrono::seconds>(timeout).count(), taken, output());
}

void HubUnderTest::plan(std::function<void()> write_once, Duration period) {
  {
    const std::lock_guard lock(planner_mutex_);
    write_once_ = std::move(write_once);
    period_ = period;
    planning_ = true;
  }
  if (planner_.joinable()) return;
  planner_ = std::thread([this] {
    for (;;) {
      Duration pause{};
      {
        const std::lock_guard lock(planner_mutex_);
        if (!planning_) return;
        write_once_();
        pause = period_;
      }
      std::this_thread::sleep_for(pause);
    }
  });
}

void HubUnderTest::stop_planner() {
  {
    const std::lock_guard lock(planner_mutex_);
    planning_ = false;
  }
  if (planner_.joinable()) planner_.join();
  EXPECT_EQ(failed_writes_.exchange(0), 0) << "the planner's commands could not all be written";
}

void HubUnderTest::sim_input(const std::string& hub, const std::string& signal, bool active) {
  if (!sim_) sim_ = std::make_shared<SimWriters>();
  if (sim_->input == nullptr) {
    ASSERT_NO_FATAL_FAILURE(make_writer(sim_->input, sim::kSimInputTopic));
    waits_.pop_back();  // matched here, not by start()
    ASSERT_NO_FATAL_FAILURE(match(*sim_->input, sim::kSimInputTopic, patience_, output()));
  }
  const hub_msgs_msg_dds__SimInput_ input{wire(hub), wire(signal), active};
  ASSERT_TRUE(sim_->input->write(input).is_ok());
}

void HubUnderTest::sim_fault(const std::string& hub, const std::string& device, const std::string& fault,
                             std::uint32_t value) {
  if (!sim_) sim_ = std::make_shared<SimWriters>();
  if (sim_->fault == nullptr) {
    ASSERT_NO_FATAL_FAILURE(make_writer(sim_->fault, sim::kSimFaultTopic));
    waits_.pop_back();
    ASSERT_NO_FATAL_FAILURE(match(*sim_->fault, sim::kSimFaultTopic, patience_, output()));
  }
  const hub_msgs_msg_dds__SimFault_ message{wire(hub), wire(device), wire(fault), value};
  ASSERT_TRUE(sim_->fault->write(message).is_ok());
}

std::string HubUnderTest::hub_file(const std::string& hub, const std::string& layout,
                                   const std::vector<std::pair<std::string, std::string>>& edits) {
  const std::string shipped = config_dir() + "/hubs/" + hub + "/" + hub + ".yaml";
  std::ifstream in(shipped);
  std::stringstream text;
  text << in.rdbuf();
  std::string content = text.str();
  EXPECT_FALSE(content.empty()) << shipped;
  std::vector<std::pair<std::string, std::string>> all = {{"layout: node_type", "layout: " + layout}};
  all.insert(all.end(), edits.begin(), edits.end());
  for (const auto& [from, to] : all) {
    const auto at = content.find(from);
    EXPECT_NE(at, std::string::npos) << "'" << from << "' not in " << shipped;
    if (at != std::string::npos) content.replace(at, from.size(), to);
  }
  // A folder of its own per file: the domain id makes it unique among the tests running now.
  const auto dir =
      std::filesystem::temp_directory_path() /
      fmt::format("hubrt-hub-file-{}-{}-{}", getpid(), domain_ ? domain_->domain_id() : 0, files_.size());
  std::filesystem::create_directories(dir);
  const std::string path = (dir / (hub + ".yaml")).string();
  std::ofstream(path) << content;
  files_.push_back(path);
  return path;
}

::testing::AssertionResult HubUnderTest::stops_cleanly(int signal) {
  if (!hub_) return ::testing::AssertionFailure() << "no hubd started";
  if (!hub_->process().signal(signal)) return ::testing::AssertionFailure() << "cannot signal hubd";
  auto status = hub_->process().wait(patience_);
  if (!status) return ::testing::AssertionFailure() << status.error().message << "\nhubd:\n" << output();
  if (!status->exited_with(0)) {
    return ::testing::AssertionFailure() << status->describe() << " after signal " << signal << "\nhubd:\n"
                                         << output();
  }
  if (output().find("outputs driven to their safe state") == std::string::npos) {
    return ::testing::AssertionFailure() << "no 'outputs driven to their safe state'\nhubd:\n" << output();
  }
  return ::testing::AssertionSuccess();
}

}  // namespace hubrt::test_support
