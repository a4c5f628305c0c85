// Whether a path names a configuration file that can be read, and if not, what it is instead:
// a missing file, a directory, a symbolic link loop, a dangling link, a FIFO or a device. Used
// by YamlMap::load_file and by hubd when it looks for board and hub files, so that "does not
// exist" is said only of files that do not exist.
#pragma once

#include <cstddef>
#include <istream>
#include <optional>
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

// The whole of `in`, or nullopt when it holds more than `max_bytes`. The text grows with what is
// read (at most one 4 KiB chunk beyond the bound is read), rather than being read into a buffer of
// max_bytes + 1 made first: that buffer (1 MiB for a board or hub file of a few KiB) was zeroed
// page by page, and a freed allocation that large made glibc raise its mmap threshold to it
// (mallopt(3), M_MMAP_THRESHOLD: dynamic), so that Cyclone's 192 KiB receive buffers, allocated
// later, came out of the heap pages that read had dirtied (all resident) instead of mappings of
// their own that become resident only as far as they are used: +0.3 MB of hubd's RSS.
// Thread-safe for distinct streams.
std::optional<std::string> read_at_most(std::istream& in, std::size_t max_bytes);

}  // namespace hubrt::config
