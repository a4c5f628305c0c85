#include "hubrt/config/config_file.h"

#include <array>
#include <filesystem>
#include <system_error>

#include <fmt/format.h>

namespace hubrt::config {
namespace fs = std::filesystem;

namespace {

Error problem(ErrorCode code, const std::string& path, std::string_view what) {
  return make_error(code, fmt::format("{}: {}", path, what));
}

Error missing(const std::string& path) {
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(path, ec))) {
    const fs::path target = fs::read_symlink(path, ec);
    return problem(ErrorCode::kNotFound, path,
                   fmt::format("is a symbolic link to '{}', which does not exist", target.string()));
  }
  return problem(ErrorCode::kNotFound, path, "does not exist");
}

}  // namespace

Expected<void> require_regular_file(const std::string& path) {
  std::error_code ec;
  // fs::status follows links; stat(2) fails with ELOOP on a link loop (here or in a folder on the
  // way) and with ENOENT/ENOTDIR when something on the way is missing.
  const fs::file_status status = fs::status(path, ec);
  if (ec == std::errc::too_many_symbolic_link_levels) {
    return problem(ErrorCode::kInvalidArgument, path,
                   "is a symbolic link loop (too many levels of symbolic links)");
  }
  if (ec == std::errc::no_such_file_or_directory || ec == std::errc::not_a_directory ||
      status.type() == fs::file_type::not_found) {
    return missing(path);
  }
  if (ec) return problem(ErrorCode::kIo, path, fmt::format("cannot be examined: {}", ec.message()));
  switch (status.type()) {
    case fs::file_type::regular:
      return {};
    case fs::file_type::directory:
      return problem(ErrorCode::kInvalidArgument, path, "is a directory, not a file");
    default:
      return problem(ErrorCode::kInvalidArgument, path, "is not a regular file (a FIFO, socket or device)");
  }
}

std::optional<std::string> read_at_most(std::istream& in, std::size_t max_bytes) {
  std::string text;
  std::array<char, 4096> chunk{};
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    const auto n = static_cast<std::size_t>(in.gcount());
    if (n > max_bytes - text.size()) return std::nullopt;
    text.append(chunk.data(), n);
  }
  return text;
}

}  // namespace hubrt::config
