// The registry's hub types against the folders they were registered from (hubs/HubTypes.cmake):
// a board file names its hub type by HubType::name() (`hub: dock_ecu`), and its package installs
// the board program built from the folder of that name (hubd_board_<folder>, firmware/hubd). A hub
// type named unlike its folder would get a board program that refuses its own board.
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/assembly/hub_types.h"
#include "hubrt/hub_api/hub_type.h"

namespace hubrt::assembly {
namespace {

std::vector<std::string> registered_folders() {
  std::vector<std::string> folders;
  std::istringstream list(HUBRT_HUB_TYPE_FOLDERS);  // "dock_ecu,rsp_ecu,...", in registry order
  for (std::string folder; std::getline(list, folder, ',');) folders.push_back(folder);
  return folders;
}

TEST(HubTypeRegistry, EachHubTypeIsNamedAsTheFolderItWasRegisteredFrom) {
  const std::vector<std::string> folders = registered_folders();
  const auto types = hub_types();
  ASSERT_EQ(types.size(), folders.size());
  for (std::size_t i = 0; i < types.size(); ++i) {
    EXPECT_EQ(types[i]->name(), folders[i]) << "registered from hubs/" << folders[i] << "/";
    EXPECT_EQ(find_hub_type(folders[i]), types[i]);
  }
}

}  // namespace
}  // namespace hubrt::assembly
