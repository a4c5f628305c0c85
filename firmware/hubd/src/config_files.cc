#include "config_files.h"

#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hubrt/config/config_file.h"

namespace hubrt::hubd {
namespace fs = std::filesystem;

std::vector<std::string> search_folders(const std::string& kind) {
  std::vector<std::string> folders;
  // NOLINTNEXTLINE(concurrency-mt-unsafe): read once at start-up, before any thread exists
  if (const char* dir = std::getenv("HUBRT_CONFIG_DIR"); dir != nullptr && *dir != '\0') {
    folders.push_back(fmt::format("{}/{}", dir, kind));
  }
  folders.push_back(fmt::format("/etc/hubrt/{}", kind));
  folders.push_back(fmt::format("/usr/share/hubrt/{}", kind));
#ifdef HUBRT_SOURCE_DIR
  folders.push_back(fmt::format("{}/{}", HUBRT_SOURCE_DIR, kind));
#endif
  return folders;
}

Expected<std::string> find_config_file(const std::string& kind, const std::string& name_or_path) {
  std::error_code ec;
  // A bare name is a file in the current folder only when it is one: `--hub dock_ecu` run from
  // hubs/ (where dock_ecu is a folder) still means the hub type.
  if (name_or_path.find('/') != std::string::npos || fs::is_regular_file(name_or_path, ec)) {
    auto usable = config::require_regular_file(name_or_path);
    if (!usable)
      return make_error(usable.error().code, fmt::format("{} file {}", kind, usable.error().message));
    return name_or_path;
  }
  std::vector<std::string> tried;
  for (const std::string& folder : search_folders(kind)) {
    std::vector<std::string> candidates;
    if (kind == "hubs")
      candidates.push_back(fmt::format("{}/{}/{}.yaml", folder, name_or_path, name_or_path));
    candidates.push_back(fmt::format("{}/{}.yaml", folder, name_or_path));
    for (const std::string& candidate : candidates) {
      auto usable = config::require_regular_file(candidate);
      if (usable) return candidate;
      // Only a file that is not there sends the search on; one that is there but cannot be used
      // (a directory, a link loop) is what the user meant, and its problem is the answer.
      if (usable.error().code != ErrorCode::kNotFound) {
        return make_error(usable.error().code, fmt::format("{} file {}", kind, usable.error().message));
      }
      tried.push_back(candidate);
    }
  }
  return make_error(ErrorCode::kNotFound, fmt::format("no {} file named '{}'; looked for: {}", kind,
                                                      name_or_path, fmt::join(tried, ", ")));
}

}  // namespace hubrt::hubd
