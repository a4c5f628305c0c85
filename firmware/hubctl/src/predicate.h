// A condition on a State, as a scenario writes it: "<field path> <operator> [<value>]".
//
//   path      dotted field names; a list element by index or, for lists of structs with a name
//             field, by that name: "at", "last_result.ok", "slots[2].occupied",
//             "slots[smart_tool].occupied", "tools[filter_tool].at"
//   operator  ==  !=  <  <=  >  >=      numbers (compared to 1e-6 relative), strings (== and !=
//                                        only), booleans (true / false)
//             contains / lacks           a list has / has no element that contains the value (a
//                                        string element as a substring); a string, as substring
//             empty / not_empty          a list or string, no value
//   value     the rest of the text, surrounding quotes removed: "error_list contains 'pressure'"
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "hubrt/base/status.h"

namespace hubrt::hubctl {

enum class Operator : std::uint8_t { kEq, kNe, kLt, kLe, kGt, kGe, kContains, kLacks, kEmpty, kNotEmpty };

struct PathPart {
  std::string field;
  bool indexed = false;
  bool by_name = false;   // [name] rather than [number]
  std::size_t index = 0;  // [number]
  std::string name;       // [name]
};

struct Predicate {
  std::string text;  // as written
  std::vector<PathPart> path;
  Operator op = Operator::kEq;
  std::string value;
};

// Parses one predicate. Errors (kInvalidArgument): no path, unknown operator (the message lists
// them), a value missing or given where none belongs, a malformed path. Thread-safe.
Expected<Predicate> parse_predicate(std::string_view text);

struct PredicateVerdict {
  bool holds = false;
  // Cannot be evaluated at all (no such field, operator does not fit the field's type): waiting
  // longer will not help.
  bool broken = false;
  std::string detail;  // what the field is, e.g. "at is \"float\""; why broken
};

// Evaluates `predicate` on a State converted to JSON (msgs::to_json). Thread-safe.
PredicateVerdict evaluate(const Predicate& predicate, const nlohmann::ordered_json& state);

}  // namespace hubrt::hubctl
