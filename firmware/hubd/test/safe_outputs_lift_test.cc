// `hubd --safe-outputs` stops the Tool ECU's lift drive: one Modbus write (control word 0: power
// stage off, the lift held on its brake) with a short timeout, best effort, logged. Against the
// lift drive simulator's real libmodbus server on loopback, reached through the Linux backend
// with the program's libmodbus, as on a board: a drive left enabled and moving by a killed hub is
// stopped; a drive that does not answer is reported NOT STOPPED within the timeout, and the
// GPIO outputs' exit status is not changed by it.
#include <chrono>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>

#include "hubrt/assembly/hub_types.h"
#include "hubrt/assembly/linux_device_libraries.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/lift_drive_server.h"
#include "hubrt/hal/linux/backend.h"
#include "hubrt/protocol/lift_drive_modbus.h"

#include "safe_outputs.h"

namespace hubrt::hubd {
namespace {

namespace ld = protocol::lift_drive;
using std::chrono::milliseconds;
using ::testing::HasSubstr;

std::string source(const std::string& relative) {
  return std::string(HUBRT_SOURCE_DIR) + "/" + relative;
}

class SafeOutputsLiftTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto started = hal::fake::LiftDriveServer::start(drive_, clock_);
    ASSERT_TRUE(started) << started.error().message;
    server_ = std::move(*started);
    auto board = hal::load_board(source("boards/host-sim.yaml"));
    ASSERT_TRUE(board) << board.error().message;
    board_ = std::move(*board);
    // The board's lift drive at the simulator's port, as a Pi's board names its drive's address.
    hal::BoardModbusDevice& lift = board_.modbus.front();
    ASSERT_EQ(lift.config.device, "lift_drive");
    lift.config.endpoint = hal::ModbusTcpEndpoint{"127.0.0.1", server_->port()};
    auto hub = config::load_hub_config(source("hubs/tool_ecu/tool_ecu.yaml"));
    ASSERT_TRUE(hub) << hub.error().message;
    hub_ = std::move(*hub);
    // Left by a killed hub: enabled, moving up at 100 mm/s toward 200 mm.
    const std::array<std::uint16_t, 2> target_speed{2000, 100};
    ASSERT_EQ(drive_.write_holding(ld::holding::kTargetPosition, target_speed, now()),
              hal::fake::ModbusException::kNone);
    const std::array<std::uint16_t, 1> run{ld::control::kEnable | ld::control::kMove};
    ASSERT_EQ(drive_.write_holding(ld::holding::kControlWord, run, now()), hal::fake::ModbusException::kNone);
    ASSERT_NE(status() & ld::status::kMoving, 0);
  }

  Time now() const { return clock_.now().mono; }
  std::uint16_t status() { return drive_.read(now()).status_word(); }

  ManualClock clock_;
  hal::fake::LiftDrive drive_{hal::fake::LiftDriveConfig{}, clock_.now().mono};
  std::unique_ptr<hal::fake::LiftDriveServer> server_;
  hal::BoardConfig board_;
  config::HubConfig hub_;
  hal::LinuxBackend backend_{assembly::linux_device_libraries()};
  std::ostringstream text_;
  spdlog::logger log_{"test", std::make_shared<spdlog::sinks::ostream_sink_mt>(text_)};
};

TEST_F(SafeOutputsLiftTest, ADriveLeftMovingIsStopped) {
  stop_devices(hub_, board_, &backend_, log_);
  EXPECT_EQ(drive_.read(now()).control_word(), 0) << text_.str();
  EXPECT_EQ(status() & (ld::status::kEnabled | ld::status::kMoving), 0) << "power stage off, not moving";
  EXPECT_THAT(text_.str(), HasSubstr("lift_drive: stopped (lift_drive (tcp 127.0.0.1:"));
  EXPECT_THAT(text_.str(), HasSubstr("control word 0 written: power stage off"));
}

TEST_F(SafeOutputsLiftTest, ADriveThatDoesNotAnswerIsReportedWithinTheTimeout) {
  server_->set_answering(false);
  const auto start = std::chrono::steady_clock::now();
  stop_devices(hub_, board_, &backend_, log_);
  const auto took = std::chrono::steady_clock::now() - start;
  // One connect and one request, each bounded by kDeviceStopTimeout; generous for a loaded machine.
  EXPECT_LT(took, 2 * kDeviceStopTimeout + milliseconds(500));
  EXPECT_THAT(text_.str(), HasSubstr("lift_drive: NOT STOPPED, left to its own communication watchdog"));
  EXPECT_NE(status() & ld::status::kEnabled, 0) << "nothing reached the drive";
}

TEST_F(SafeOutputsLiftTest, TheToolEcuHasTheLiftDriveToStopAndTheRspEcuNothing) {
  const hub_api::HubType* tool = assembly::find_hub_type("tool_ecu");
  ASSERT_NE(tool, nullptr);
  const auto reports = tool->stop_devices(hub_, board_, backend_, kDeviceStopTimeout);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_EQ(reports[0].device, "lift_drive");
  EXPECT_TRUE(reports[0].stopped) << reports[0].message;
  const hub_api::HubType* rsp = assembly::find_hub_type("rsp_ecu");
  ASSERT_NE(rsp, nullptr);
  auto rsp_hub = config::load_hub_config(source("hubs/rsp_ecu/rsp_ecu.yaml"));
  ASSERT_TRUE(rsp_hub);
  EXPECT_TRUE(rsp->stop_devices(*rsp_hub, board_, backend_, kDeviceStopTimeout).empty());
}

}  // namespace
}  // namespace hubrt::hubd
