// Where hubd finds a board or hub file given by name: `--board rpi4-dock-ecu` means
// rpi4-dock-ecu.yaml in the first of the search folders that has it.
#pragma once

#include <string>
#include <vector>

#include "hubrt/base/status.h"

namespace hubrt::hubd {

// Search folders, in order: $HUBRT_CONFIG_DIR/<kind>, /etc/hubrt/<kind>, /usr/share/hubrt/<kind>,
// then, in development builds, the source tree's folders. <kind> is "boards" or "hubs".
std::vector<std::string> search_folders(const std::string& kind);

// `name_or_path` as a file if it is one (or contains a '/'); otherwise <folder>/<name>.yaml for
// boards and <folder>/<name>/<name>.yaml or <folder>/<name>.yaml for hubs, in search order.
// Errors: kNotFound listing every place looked at; for a path given, or a candidate found in a
// search folder, that is not a usable file: "<kind> file <path>: <problem>" with the code of
// config::require_regular_file (a directory, a symbolic link loop, a dangling link, ...).
Expected<std::string> find_config_file(const std::string& kind, const std::string& name_or_path);

}  // namespace hubrt::hubd
