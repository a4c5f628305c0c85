// The wiring tables in docs/deploy.md are what `make deploy-docs` generates from boards/ today: a
// board file changed without regenerating the guide fails here.
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "hubrt/hal/board/board_loader.h"
#include "hubrt/packaging/wiring_tables.h"

namespace hubrt::packaging {
namespace {

const std::filesystem::path kSourceDir = HUBRT_SOURCE_DIR;

TEST(DeployGuide, WiringTablesMatchTheBoardFiles) {
  std::vector<hal::BoardConfig> boards;
  for (const auto& entry : std::filesystem::directory_iterator(kSourceDir / "boards")) {
    if (entry.path().extension() != ".yaml") continue;
    auto board = hal::load_board(entry.path().string());
    ASSERT_TRUE(board) << board.error().message;
    boards.push_back(std::move(*board));
  }
  ASSERT_FALSE(boards.empty());
  const std::filesystem::path guide = kSourceDir / "docs" / "deploy.md";
  std::ifstream in(guide, std::ios::binary);
  ASSERT_TRUE(in) << "cannot read " << guide;
  const std::string document((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto regenerated = replace_generated_section(document, wiring_section(std::move(boards)));
  ASSERT_TRUE(regenerated) << guide << ": " << regenerated.error().message;
  EXPECT_EQ(*regenerated, document) << guide << " is out of date: run `make deploy-docs`";
}

}  // namespace
}  // namespace hubrt::packaging
