// Whether a path names a configuration file that can be read, and if not, what it is instead:
// a missing file, a directory, a symbolic link loop, a dangling link, a FIFO or a device. Used
// by YamlMap::load_file and by hubd when it looks for board and hub files, so that "does not
// exist" is said only of files that do not exist.
#pragma once

#include <string>

#include "hubrt/base/status.h"

namespace hubrt::config {

// Succeeds when `path` (after following symbolic links) is a regular file. Errors, each as
// "<path>: <problem>":
//   kNotFound         "does not exist", or "is a symbolic link to '<target>', which does not exist"
//   kInvalidArgument  "is a directory, not a file"; "is a symbolic link loop (too many levels of
//                     symbolic links)"; "is not a regular file (a FIFO, socket or device)"
//   kIo               "cannot be examined: <reason>", e.g. a folder on the way is not readable
// Thread-safe; reads the file system only.
Expected<void> require_regular_file(const std::string& path);

}  // namespace hubrt::config
