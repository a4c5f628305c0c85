// hubd running the operator hub on the linux backend in the kernel tier's guest: a uinput virtual
// keyboard stands in for a USB keyboard-wedge RFID reader and types badges; hubd reads them
// through libevdev (grabbed) and verifies them against the test allow-list; the test is the
// planner over Cyclone DDS on loopback, in a domain of its own. Skips outside the tier.
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <libevdev/libevdev-uinput.h>
#include <libevdev/libevdev.h>
#include <linux/input.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/kernel_test/environment.h"
#include "hubrt/test_support/hub_under_test.h"

#include "operator_messages.h"

namespace hubrt::operator_hub {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

// Generous: an emulated (tcg) guest running sanitizer builds.
constexpr auto kPatience = seconds(30);
const std::string kDir = HUBRT_OPERATOR_HUB_DIR;

hub_msgs::OperatorPanelStateView view(const OperatorPanelState& state) {
  return hub_msgs::OperatorPanelStateView(state);
}

class HubdOperatorKernelTest : public ::testing::Test {
 protected:
  void SetUp() override {
    HUBRT_SKIP_OUTSIDE_KERNEL_TIER();
    libevdev* dev = libevdev_new();
    libevdev_set_name(dev, "hubrt kernel-tier RFID reader");
    libevdev_enable_event_type(dev, EV_KEY);
    for (unsigned code : {KEY_0, KEY_1, KEY_2, KEY_3, KEY_4, KEY_5, KEY_6, KEY_7, KEY_8, KEY_9, KEY_ENTER}) {
      libevdev_enable_event_code(dev, EV_KEY, code, nullptr);
    }
    const int rc = libevdev_uinput_create_from_device(dev, LIBEVDEV_UINPUT_OPEN_MANAGED, &uinput_);
    libevdev_free(dev);
    ASSERT_EQ(rc, 0) << "uinput (is the uinput module loaded?): " << rc;
    const std::string devnode = libevdev_uinput_get_devnode(uinput_);
    for (int i = 0; i < 200 && ::access(devnode.c_str(), R_OK) != 0; ++i)
      std::this_thread::sleep_for(milliseconds(10));

    // A board with only the reader, and the shipped hub file without the button, with the test
    // allow-list (into TMPDIR: the guest's root is read-only).
    const auto dir = std::filesystem::temp_directory_path() / "hubrt-operator-kernel";
    std::filesystem::create_directories(dir);
    board_ = (dir / "operator-uinput.yaml").string();
    std::ofstream(board_) << "board: operator-uinput\narch: x86_64\nhub: operator_hub\nrfid:\n"
                          << "  operator_rfid: {evdev: {device: " << devnode << ", grab: true}}\n";
    std::ifstream in(kDir + "/operator_hub.yaml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("allow_list: operators.list"), 26, "allow_list: " + kDir + "/test/operators.list");
    const auto button = text.find("    confirm_button:");
    text.erase(button, text.find('\n', button) - button + 1);
    hub_file_ = (dir / "operator_hub.yaml").string();
    std::ofstream(hub_file_) << text;

    ASSERT_NO_FATAL_FAILURE(hub_.open("kernel-test-planner"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_writer(command_writer_, "/operator_panel/command"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_stream(states_, "/operator_hub/panel/state"));
    ASSERT_NO_FATAL_FAILURE(hub_.start({.board = board_,
                                        .hub = hub_file_,
                                        .extra_args = {"--backend", "linux"},
                                        .start_patience = kernel_test::kHubdStartPatience}));
  }
  void TearDown() override {
    hub_.end_hub();  // before the reader it holds goes
    if (uinput_ != nullptr) libevdev_uinput_destroy(uinput_);
  }

  // The planner's verify command, resent while waiting (the command timeout is 1 s).
  bool verify_until(const std::function<bool(const OperatorPanelState&)>& predicate) {
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    auto next_command = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() < deadline) {
      if (std::chrono::steady_clock::now() >= next_command) {
        hub_msgs::OperatorPanelCommand c;
        c.set_target_type("operator_panel");
        c.set_target_name("panel");
        c.set_action("verify");
        if (!command_writer_->write(c.wire()).is_ok()) return false;
        next_command += milliseconds(50);
      }
      const Result<bool> taken = states_->reader().take_next(state_);
      if (taken.is_ok() && taken.value() && predicate(state_.get())) return true;
      std::this_thread::sleep_for(milliseconds(2));
    }
    return false;
  }

  void type(std::initializer_list<unsigned> keys) {
    for (unsigned code : keys) {
      libevdev_uinput_write_event(uinput_, EV_KEY, code, 1);
      libevdev_uinput_write_event(uinput_, EV_SYN, SYN_REPORT, 0);
      libevdev_uinput_write_event(uinput_, EV_KEY, code, 0);
      libevdev_uinput_write_event(uinput_, EV_SYN, SYN_REPORT, 0);
    }
  }

  libevdev_uinput* uinput_ = nullptr;
  std::string board_;
  std::string hub_file_;
  dds::Writer<OperatorPanelCommand>* command_writer_ = nullptr;
  test_support::StateStream<OperatorPanelState>* states_ = nullptr;
  dds::Sample<OperatorPanelState> state_;
  test_support::HubUnderTest hub_{kPatience};
};

TEST_F(HubdOperatorKernelTest, AUinputKeyboardTypesABadgeAndTheHubVerifiesIt) {
  ASSERT_TRUE(verify_until([](const OperatorPanelState& s) {
    return view(s).reader_open() && view(s).fresh_msg();
  })) << hub_.output();
  type({KEY_0, KEY_0, KEY_0, KEY_4, KEY_1, KEY_2, KEY_3, KEY_4, KEY_5, KEY_6, KEY_ENTER});
  ASSERT_TRUE(verify_until([](const OperatorPanelState& s) {
    return view(s).operator_verified() && view(s).operator_name() == "Anna Svensson";
  })) << hub_.output();
  EXPECT_EQ(view(state_.get()).last_badge_tag(), "9ad4c64a");

  type({KEY_9, KEY_9, KEY_9, KEY_ENTER});
  ASSERT_TRUE(verify_until([](const OperatorPanelState& s) { return view(s).badge_reads() == 2; }))
      << hub_.output();
  EXPECT_EQ(view(state_.get()).last_badge_reason(), "unknown badge");
  EXPECT_EQ(view(state_.get()).operator_name(), "Anna Svensson");
  EXPECT_EQ(hub_.output().find("0004123456"), std::string::npos) << hub_.output();
}

}  // namespace
}  // namespace hubrt::operator_hub
