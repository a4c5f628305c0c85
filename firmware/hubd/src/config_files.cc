#include "config_files.h"

#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>

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
  if (name_or_path.find('/') != std::string::npos || fs::is_regular_file(name_or_path, ec)) {
    if (fs::is_regular_file(name_or_path, ec)) return name_or_path;
    return make_error(ErrorCode::kNotFound, fmt::format("{} file '{}' does not exist", kind, name_or_path));
  }
  std::vector<std::string> tried;
  for (const std::string& folder : search_folders(kind)) {
    std::vector<std::string> candidates;
    if (kind == "hubs")
      candidates.push_back(fmt::format("{}/{}/{}.yaml", folder, name_or_path, name_or_path));
    candidates.push_back(fmt::format("{}/{}.yaml", folder, name_or_path));
    for (const std::string& candidate : candidates) {
      if (fs::is_regular_file(candidate, ec)) return candidate;
      tried.push_back(candidate);
    }
  }
  return make_error(ErrorCode::kNotFound, fmt::format("no {} file named '{}'; looked for: {}", kind,
                                                      name_or_path, fmt::join(tried, ", ")));
}

}  // namespace hubrt::hubd
