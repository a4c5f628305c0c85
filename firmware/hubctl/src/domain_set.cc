#include "domain_set.h"

#include <algorithm>
#include <charconv>

#include <fmt/format.h>

#include "hubrt/dds/domain.h"

namespace hubrt::hubctl {
namespace {

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

Error bad(std::string_view whole, std::string_view message) {
  return make_error(ErrorCode::kInvalidArgument, fmt::format("domains '{}': {}", whole, message));
}

// One id: digits only (no sign, no blanks inside), at most dds::kMaxDomainId.
Expected<std::uint32_t> domain_id(std::string_view whole, std::string_view text) {
  text = trimmed(text);
  std::uint32_t id = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
  if (text.empty() || ec == std::errc::invalid_argument || end != text.data() + text.size()) {
    return bad(whole, fmt::format("'{}' is not a domain id", text));
  }
  if (ec == std::errc::result_out_of_range || id > dds::kMaxDomainId) {
    return bad(whole, fmt::format("domain {} is above {}, the highest id Cyclone's port numbers allow", text,
                                  dds::kMaxDomainId));
  }
  return id;
}

}  // namespace

Expected<std::vector<std::uint32_t>> parse_domain_set(std::string_view text) {
  std::vector<std::uint32_t> ids;
  if (trimmed(text).empty()) return bad(text, "no domain id");
  std::string_view rest = text;
  for (;;) {
    const auto comma = rest.find(',');
    const std::string_view part = trimmed(rest.substr(0, comma));
    if (part.empty()) return bad(text, "an empty part between commas");
    std::uint32_t first = 0;
    std::uint32_t last = 0;
    if (const auto dash = part.find('-'); dash != std::string_view::npos) {
      auto low = domain_id(text, part.substr(0, dash));
      if (!low) return std::move(low).error();
      auto high = domain_id(text, part.substr(dash + 1));
      if (!high) return std::move(high).error();
      if (*high < *low) return bad(text, fmt::format("range '{}' ends before it begins", part));
      first = *low;
      last = *high;
    } else {
      auto id = domain_id(text, part);
      if (!id) return std::move(id).error();
      first = last = *id;
    }
    if (ids.size() + (last - first + 1) > kMaxPlantDomains) {
      return bad(text, fmt::format("more than {} domains (one participant each)", kMaxPlantDomains));
    }
    for (std::uint32_t id = first; id <= last; ++id) ids.push_back(id);
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  std::sort(ids.begin(), ids.end());
  if (const auto twice = std::adjacent_find(ids.begin(), ids.end()); twice != ids.end()) {
    return bad(text, fmt::format("domain {} is named twice", *twice));
  }
  return ids;
}

std::string format_domain_set(const std::vector<std::uint32_t>& ids) {
  std::string out;
  for (std::size_t i = 0; i < ids.size();) {
    std::size_t j = i;
    while (j + 1 < ids.size() && ids[j + 1] == ids[j] + 1) ++j;
    if (!out.empty()) out += ',';
    out += j == i ? fmt::format("{}", ids[i]) : fmt::format("{}-{}", ids[i], ids[j]);
    i = j + 1;
  }
  return out;
}

}  // namespace hubrt::hubctl
