// Every file in broken/ must be rejected with exactly the message its first line announces:
//   # expect: {file}:12:5: gpio.inputs.x.line: ...
// where {file} stands for the path the loader was given.
#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "hubrt/hal/board/board_loader.h"

namespace hubrt::hal {
namespace {

namespace fs = std::filesystem;

const fs::path kBrokenDir = HUBRT_BROKEN_BOARDS_DIR;

std::vector<std::string> broken_files() {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(kBrokenDir)) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string expected_message(const fs::path& path) {
  std::ifstream in(path);
  std::string first_line;
  std::getline(in, first_line);
  const std::string prefix = "# expect: ";
  if (!first_line.starts_with(prefix)) return {};
  std::string message = first_line.substr(prefix.size());
  const std::string placeholder = "{file}";
  for (auto at = message.find(placeholder); at != std::string::npos; at = message.find(placeholder)) {
    message.replace(at, placeholder.size(), path.string());
  }
  return message;
}

TEST(BrokenBoards, TheCorpusIsThere) {
  EXPECT_GE(broken_files().size(), 20U);
}

class BrokenBoard : public ::testing::TestWithParam<std::string> {};

TEST_P(BrokenBoard, IsRejectedWithTheAnnouncedMessage) {
  const fs::path path = kBrokenDir / GetParam();
  const std::string expected = expected_message(path);
  ASSERT_FALSE(expected.empty()) << path << " does not start with '# expect: <message>'";
  auto loaded = load_board(path.string());
  ASSERT_FALSE(loaded.is_ok()) << path << " was accepted";
  EXPECT_EQ(loaded.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(loaded.error().message, expected);
}

std::string test_name(const ::testing::TestParamInfo<std::string>& file) {
  std::string name = file.param.substr(0, file.param.size() - std::string(".yaml").size());
  for (char& c : name) {
    if (c == '-' || c == '.') c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BrokenBoard, ::testing::ValuesIn(broken_files()), test_name);

}  // namespace
}  // namespace hubrt::hal
