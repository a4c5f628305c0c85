#include "hubrt/hal/board/board_requirements.h"

#include <gtest/gtest.h>

#include "hubrt/hal/board/board_loader.h"

namespace hubrt::hal {
namespace {

constexpr const char* kBoardText = R"(board: x
arch: arm64
hub: dock_ecu
gpio:
  chips:
    main: {name: gpiochip0}
  inputs:
    dock.slot.smart_tool: {chip: main, line: 5}
  outputs:
    dock.slot.filter_tool: {chip: main, line: 6, safe: false}
can:
  tool_bus: {interface: can0}
)";

class BoardRequirementsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto loaded = load_board_string(kBoardText, "boards/x.yaml");
    ASSERT_TRUE(loaded.is_ok()) << loaded.error().message;
    board_ = std::move(*loaded);
  }
  BoardConfig board_;
};

TEST_F(BoardRequirementsTest, PassesWhenEverythingIsThereAsTheRightKind) {
  const BoardRequirements needs{
      "dock_ecu", {"dock.slot.smart_tool"}, {"dock.slot.filter_tool"}, {"tool_bus"}, {}, {}};
  EXPECT_TRUE(check_requirements(board_, needs).is_ok());
}

TEST_F(BoardRequirementsTest, NamesTheLineOfADeclarationOfTheWrongKind) {
  const BoardRequirements needs{"dock_ecu", {"dock.slot.filter_tool"}, {}, {}, {}, {}};
  auto checked = check_requirements(board_, needs);
  ASSERT_FALSE(checked.is_ok());
  EXPECT_EQ(checked.error().code, ErrorCode::kFailedPrecondition);
  EXPECT_EQ(checked.error().message,
            "hub dock_ecu needs input 'dock.slot.filter_tool' but boards/x.yaml declares it as an output "
            "(line 10)");
}

TEST_F(BoardRequirementsTest, SaysWhatIsMissing) {
  const BoardRequirements needs{"dock_ecu", {"dock.slot.smart_tool"}, {}, {}, {"lift_drive"}, {}};
  auto checked = check_requirements(board_, needs);
  ASSERT_FALSE(checked.is_ok());
  EXPECT_EQ(checked.error().message,
            "hub dock_ecu needs Modbus device 'lift_drive' but boards/x.yaml does not declare it");
  const BoardRequirements rest{"dock_ecu", {}, {}, {}, {}, {"mir"}};
  checked = check_requirements(board_, rest);
  ASSERT_FALSE(checked.is_ok());
  EXPECT_EQ(checked.error().message,
            "hub dock_ecu needs HTTP device 'mir' but boards/x.yaml does not declare it");
}

TEST_F(BoardRequirementsTest, ABusIsNotAnOutput) {
  const BoardRequirements needs{"dock_ecu", {}, {"tool_bus"}, {}, {}, {}};
  auto checked = check_requirements(board_, needs);
  ASSERT_FALSE(checked.is_ok());
  EXPECT_EQ(checked.error().message,
            "hub dock_ecu needs output 'tool_bus' but boards/x.yaml declares it as a CAN bus (line 12)");
}

TEST_F(BoardRequirementsTest, RejectsABoardWiredForAnotherHub) {
  const BoardRequirements needs{"tool_ecu", {}, {}, {}, {}, {}};
  auto checked = check_requirements(board_, needs);
  ASSERT_FALSE(checked.is_ok());
  EXPECT_EQ(checked.error().message, "boards/x.yaml (board x) is wired for hub dock_ecu, not tool_ecu");
}

}  // namespace
}  // namespace hubrt::hal
