// The smart tool node's devices going away and coming back (a GPIO expander unplugged and plugged
// in again): the run lines and inputs are opened again by themselves and the tool runs again.
#include <gtest/gtest.h>

#include "smart_tool_logic.h"
#include "smart_tool_test_support.h"

namespace hubrt::tool_ecu {
namespace {

using namespace testing;  // NOLINT(google-build-using-namespace): the fixture and its helpers

TEST_F(SmartToolLogicTest, TheRunLinesRecoverAfterTheirChipVanishesAndReturns) {
  make_ready();
  auto wiring = fake_->wiring("tool.run_forward");
  ASSERT_TRUE(wiring.is_ok());
  hal::fake::FakeGpioChip& chip = *wiring.value().chip;
  const Order loosen = action("loosen");
  ASSERT_TRUE(cycle_until(&loosen, [&] { return output() == "reverse"; })) << errors();
  ASSERT_TRUE(line("tool.run_forward"));

  chip.vanish();
  cycles(loosen, 3);
  EXPECT_EQ(output(), "idle") << "nothing drives the lines while their chip is gone";
  EXPECT_NE(errors().find("run line tool.run_forward not available"), std::string::npos) << errors();
  EXPECT_NE(errors().find("run line tool.run_reverse not available"), std::string::npos) << errors();

  chip.reappear();
  cycles(nullptr, 3);
  // Within the back-off's cap (2 s) of the chip's return every device is open again.
  ASSERT_TRUE(cycle_until(
      nullptr, [&] { return errors().find("not available") == std::string::npos; }, 60))
      << errors();
  ASSERT_TRUE(cycle_until(&loosen, [&] { return output() == "reverse"; })) << errors();
  EXPECT_TRUE(line("tool.run_forward"));
  EXPECT_TRUE(line("tool.run_reverse"));
  cycles(nullptr, 2);
  EXPECT_EQ(output(), "idle");
  EXPECT_FALSE(line("tool.run_forward"));
}

}  // namespace
}  // namespace hubrt::tool_ecu
