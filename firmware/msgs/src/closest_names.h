// "Did you mean" support shared by the registry and field-path errors.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace hubrt::msgs::detail {

// Levenshtein distance (insert, delete, substitute each cost 1).
std::size_t edit_distance(std::string_view a, std::string_view b);

// Candidates within a distance that scales with the length of `wanted` (a typo, not a different
// word), closest first, at most `max`.
std::vector<std::string> closest_names(std::string_view wanted,
                                       const std::vector<std::string_view>& candidates, std::size_t max);

}  // namespace hubrt::msgs::detail
