// Opening a board's signals as supervised devices: a signal the board lacks is an error naming it;
// a device that cannot be opened yet is handed over not open, with its reason, to be retried.
#include "hubrt/hubs/board_devices.h"

#include <gtest/gtest.h>

#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/fake_backend.h"

namespace hubrt::hubs {
namespace {

class BoardDevicesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto board = hal::load_board(std::string(HUBRT_BOARDS_DIR) + "/host-sim.yaml");
    ASSERT_TRUE(board) << board.error().message;
    board_ = std::move(*board);
    auto fake = hal::fake::FakeBackend::create(board_, clock_);
    ASSERT_TRUE(fake) << fake.error().message;
    fake_ = std::move(*fake);
  }
  [[nodiscard]] Time now() const { return clock_.now().mono; }

  ManualClock clock_;
  hal::BoardConfig board_;
  std::unique_ptr<hal::fake::FakeBackend> fake_;
};

TEST_F(BoardDevicesTest, OpensTheBoardsSignalsWithTheirWiring) {
  auto input = open_board_input(board_, *fake_, "dock", "dock.slot.smart_tool", now());
  ASSERT_TRUE(input) << input.error().message;
  EXPECT_EQ(input->health(), hal::DeviceHealth::kOpen);
  EXPECT_EQ(input->config().line, board_.find_input("dock.slot.smart_tool")->config.line);
  auto output = open_board_output(board_, *fake_, "tool changer", "rsp.lock_valve", now());
  ASSERT_TRUE(output) << output.error().message;
  EXPECT_EQ(output->health(), hal::DeviceHealth::kOpen);
  EXPECT_TRUE(output->write(true, now()).is_ok());
  EXPECT_TRUE(fake_->active("rsp.lock_valve").value());
}

TEST_F(BoardDevicesTest, ASignalTheBoardLacksIsAnErrorNamingItsOwnerAndTheBoard) {
  auto input = open_board_input(board_, *fake_, "slot 'spare2'", "dock.slot.spare2", now());
  ASSERT_FALSE(input);
  EXPECT_EQ(input.error().code, ErrorCode::kNotFound);
  EXPECT_EQ(input.error().message,
            "slot 'spare2': board " + board_.file + " has no input 'dock.slot.spare2'");
  auto output = open_board_output(board_, *fake_, "smart tool", "dock.slot.smart_tool", now());
  ASSERT_FALSE(output);
  EXPECT_NE(output.error().message.find("has no output 'dock.slot.smart_tool'"), std::string::npos);
}

TEST_F(BoardDevicesTest, ADeviceThatCannotBeOpenedYetIsHandedOverNotOpen) {
  auto wiring = fake_->wiring("dock.slot.smart_tool");
  ASSERT_TRUE(wiring.is_ok());
  wiring.value().chip->vanish();
  auto input = open_board_input(board_, *fake_, "dock", "dock.slot.smart_tool", now());
  ASSERT_TRUE(input) << "a missing chip does not stop the hub";
  EXPECT_EQ(input->health(), hal::DeviceHealth::kNeverOpened);
  EXPECT_NE(input->error().find("dock.slot.smart_tool"), std::string_view::npos) << input->error();
}

}  // namespace
}  // namespace hubrt::hubs
