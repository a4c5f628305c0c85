// mir_com's settings and hub type: the shipped hub file on the test board, settings errors that
// name the line, both layouts.
#include "mir_settings.h"

#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_loader.h"

#include "mir_com_hub_type.h"

namespace hubrt::mir_com {
namespace {

Expected<hal::BoardRequirements> requirements_of(const std::string& nodes_yaml) {
  auto root = config::YamlMap::load_string("hub: mir_com\nnodes:\n" + nodes_yaml, "mir.yaml");
  if (!root) return std::move(root).error();
  auto config = config::parse_hub_config(*root);
  if (!config) return std::move(config).error();
  return mir_com_hub_type().requirements(*config);
}

TEST(MirComHubType, TheDefaultConfigurationNeedsTheBoardsHttpDevice) {
  auto config = config::load_hub_config(std::string(HUBRT_MIR_COM_DIR) + "/mir_com.yaml");
  ASSERT_TRUE(config) << config.error().message;
  auto required = mir_com_hub_type().requirements(*config);
  ASSERT_TRUE(required) << required.error().message;
  EXPECT_EQ(required->http_devices, std::vector<std::string>{"mir"});
  for (const std::string& board_file :
       {std::string(HUBRT_MIR_COM_DIR) + "/../../boards/host-sim-mir-com.yaml",
        std::string(HUBRT_BOARDS_DIR) + "/arm64-mir-com.yaml"}) {
    auto board = hal::load_board(board_file);
    ASSERT_TRUE(board) << board.error().message;
    EXPECT_TRUE(hal::check_requirements(*board, *required)) << board_file;
  }
  EXPECT_TRUE(mir_com_hub_type().check(*config));
}

TEST(MirComSettings, BadSettingsNameTheLine) {
  constexpr std::string_view kMover =
      "  mover:\n    type: robot_mover\n    device: mir\n    robot_name: mir100\n";
  EXPECT_EQ(requirements_of(std::string(kMover)).error().message,
            "mir.yaml:4:5: nodes.mover: missing required key 'move_mission'");
  EXPECT_EQ(requirements_of(std::string(kMover) + "    move_mission: not-a-guid!\n").error().message,
            "mir.yaml:7:19: nodes.mover.move_mission: 'not-a-guid!' is not a MiR guid (hex digits and '-')");
  EXPECT_EQ(requirements_of("  poses:\n    type: pose_saver\n    device: mir\n    robot_name: mir100\n"
                            "    poll_ms: 500\n    answer_within_ms: 400\n")
                .error()
                .message,
            "mir.yaml:8:23: nodes.poses.answer_within_ms: must be longer than poll_ms");
  EXPECT_EQ(requirements_of("  lamp:\n    type: lamp\n").error().message,
            "mir.yaml:4:11: nodes.lamp.type: a mir_com hub has nodes of type 'robot_mover' or 'pose_saver', "
            "not 'lamp'");
}

TEST(MirComBoards, TheAuthorizationIsInlineOnSimulationBoardsOnly) {
  const std::string board =
      "board: b\narch: arm64\nhub: mir_com\nhttp:\n  mir: {host: 192.168.12.20, authorization: \"Basic "
      "x\"}\n";
  auto loaded = hal::load_board_string(board, "b.yaml");
  ASSERT_FALSE(loaded);
  EXPECT_EQ(
      loaded.error().message,
      "b.yaml:5:45: http.mir.authorization: an inline authorization is only allowed on a simulation board: "
      "use authorization_file");
  auto missing = hal::load_board_string(
      "board: b\narch: arm64\nhub: mir_com\nhttp:\n  mir: {host: 192.168.12.20, authorization_file: "
      "/nonexistent/x}\n",
      "b.yaml");
  ASSERT_TRUE(missing) << missing.error().message;
  auto authorization = hal::load_http_authorization(missing->http.front());
  ASSERT_FALSE(authorization);
  EXPECT_NE(authorization.error().message.find("mir: cannot read authorization_file /nonexistent/x"),
            std::string::npos)
      << authorization.error().message;
}

}  // namespace
}  // namespace hubrt::mir_com
