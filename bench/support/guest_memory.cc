#include "guest_memory.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <vector>

#include <fmt/format.h>

namespace hubrt::bench {
namespace {

struct Mapping {
  std::uint64_t start = 0;
  std::string path;  // empty for anonymous memory
  Resident kb;
};

// A whole field as a number in `base`, nullopt when it is not one.
std::optional<std::uint64_t> number(std::string_view text, int base) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value, base);
  if (error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// The mappings of an smaps text: a header line "start-end perms offset dev inode [path]" followed by
// "Key: value kB" lines, of which Rss and Anonymous are the ones kept.
std::vector<Mapping> parse_smaps(std::string_view smaps) {
  std::vector<Mapping> out;
  std::istringstream in{std::string(smaps)};
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string first;
    fields >> first;
    if (first == "Rss:" || first == "Anonymous:") {
      std::string kb;
      fields >> kb;
      if (const auto value = number(kb, 10); value && !out.empty())
        (first == "Rss:" ? out.back().kb.rss : out.back().kb.anon) += static_cast<double>(*value);
      continue;
    }
    const auto dash = first.find('-');
    if (dash == std::string::npos) continue;
    const auto start = number(std::string_view(first).substr(0, dash), 16);
    const auto end = number(std::string_view(first).substr(dash + 1), 16);
    if (!start || !end) continue;
    std::string perms, offset, device, inode, path;
    fields >> perms >> offset >> device >> inode;
    std::getline(fields >> std::ws, path);
    out.push_back(Mapping{*start, path, {}});
  }
  return out;
}

}  // namespace

std::optional<Resident> guest_rss_kb(std::string_view smaps, const std::string& emulator_path) {
  const std::vector<Mapping> mappings = parse_smaps(smaps);
  std::uint64_t boundary = std::numeric_limits<std::uint64_t>::max();
  for (const Mapping& m : mappings) {
    if (m.path == "[heap]" || m.path == emulator_path) boundary = std::min(boundary, m.start);
  }
  if (boundary == std::numeric_limits<std::uint64_t>::max()) return std::nullopt;
  Resident kb;
  for (const Mapping& m : mappings) {
    if (m.start >= boundary) continue;
    kb.rss += m.kb.rss;
    kb.anon += m.kb.anon;
  }
  return kb;
}

std::optional<Resident> emulated_guest_rss_mb(pid_t pid) {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink(fmt::format("/proc/{}/exe", pid), ec);
  if (ec || exe.filename().string().rfind("qemu-", 0) != 0) return std::nullopt;
  std::ifstream file(fmt::format("/proc/{}/smaps", pid));
  const std::string smaps((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const auto kb = guest_rss_kb(smaps, exe.string());
  if (!kb) return std::nullopt;
  return Resident{kb->rss / 1024.0, kb->anon / 1024.0};
}

}  // namespace hubrt::bench
