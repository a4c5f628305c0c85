#include "predicate.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "sample_decoder.h"

namespace hubrt::hubctl {
namespace {

struct OperatorName {
  std::string_view text;
  Operator op;
  bool takes_value;
};
constexpr OperatorName kOperators[] = {
    {"==", Operator::kEq, true},
    {"!=", Operator::kNe, true},
    {"<", Operator::kLt, true},
    {"<=", Operator::kLe, true},
    {">", Operator::kGt, true},
    {">=", Operator::kGe, true},
    {"contains", Operator::kContains, true},
    {"lacks", Operator::kLacks, true},
    {"empty", Operator::kEmpty, false},
    {"not_empty", Operator::kNotEmpty, false},
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::string_view next_word(std::string_view& rest) {
  rest = trim(rest);
  const auto end = std::min(rest.find(' '), rest.find('\t'));
  const std::string_view word = rest.substr(0, end);
  rest = end == std::string_view::npos ? std::string_view() : rest.substr(end);
  return word;
}

bool is_field_name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

Expected<std::vector<PathPart>> parse_path(std::string_view path) {
  std::vector<PathPart> parts;
  std::string_view rest = path;
  while (true) {
    PathPart part;
    std::size_t n = 0;
    while (n < rest.size() && is_field_name_char(rest[n])) ++n;
    if (n == 0) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("malformed field path '{}': expected a field "
                                    "name at '{}'",
                                    path, rest));
    }
    part.field = std::string(rest.substr(0, n));
    rest.remove_prefix(n);
    if (!rest.empty() && rest.front() == '[') {
      const auto close = rest.find(']');
      if (close == std::string_view::npos || close == 1) {
        return make_error(ErrorCode::kInvalidArgument,
                          fmt::format("malformed field path '{}': bad [...]", path));
      }
      const std::string_view inside = rest.substr(1, close - 1);
      part.indexed = true;
      std::size_t index = 0;
      const auto [end, ec] = std::from_chars(inside.data(), inside.data() + inside.size(), index);
      if (ec == std::errc() && end == inside.data() + inside.size()) {
        part.index = index;
      } else {
        part.by_name = true;
        part.name = std::string(inside);
      }
      rest.remove_prefix(close + 1);
    }
    parts.push_back(std::move(part));
    if (rest.empty()) return parts;
    if (rest.front() != '.') {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("malformed field path '{}': expected '.' or '[' at '{}'", path, rest));
    }
    rest.remove_prefix(1);
  }
}

std::string unquote(std::string_view value) {
  value = trim(value);
  if (value.size() >= 2 && (value.front() == '\'' || value.front() == '"') && value.back() == value.front()) {
    value = value.substr(1, value.size() - 2);
  }
  return std::string(value);
}

std::string keys_of(const nlohmann::ordered_json& object) {
  std::string out;
  for (const auto& [key, value] : object.items()) out += fmt::format("{}{}", out.empty() ? "" : ", ", key);
  return out;
}

// The value at `path`, or why there is none.
const nlohmann::ordered_json* resolve(const std::vector<PathPart>& path, const nlohmann::ordered_json& state,
                                      std::string& why) {
  const nlohmann::ordered_json* at = &state;
  std::string walked;
  for (const PathPart& part : path) {
    if (!at->is_object() || !at->contains(part.field)) {
      why = fmt::format("no field '{}'{} (fields: {})", part.field,
                        walked.empty() ? "" : fmt::format(" in '{}'", walked),
                        at->is_object() ? keys_of(*at) : std::string("none: not a struct"));
      return nullptr;
    }
    at = &(*at)[part.field];
    walked += (walked.empty() ? "" : ".") + part.field;
    if (!part.indexed) continue;
    if (!at->is_array()) {
      why = fmt::format("'{}' is not a list", walked);
      return nullptr;
    }
    if (!part.by_name) {
      if (part.index >= at->size()) {
        why = fmt::format("'{}' has {} element(s); there is no [{}]", walked, at->size(), part.index);
        return nullptr;
      }
      at = &(*at)[part.index];
    } else {
      const nlohmann::ordered_json* found = nullptr;
      std::string names;
      for (const auto& element : *at) {
        if (!element.is_object() || !element.contains("name") || !element["name"].is_string()) continue;
        const auto& name = element["name"].get_ref<const std::string&>();
        if (name == part.name) found = &element;
        names += fmt::format("{}{}", names.empty() ? "" : ", ", name);
      }
      if (found == nullptr) {
        why = fmt::format("'{}' has no element named '{}' (names: {})", walked, part.name,
                          names.empty() ? "none" : names);
        return nullptr;
      }
      at = found;
    }
    walked += fmt::format("[{}]", part.by_name ? part.name : std::to_string(part.index));
  }
  return at;
}

std::optional<double> parse_number(std::string_view text) {
  if (text == "nan" || text == "NaN") return std::nan("");
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::optional<bool> parse_bool(std::string_view text) {
  if (text == "true" || text == "1") return true;
  if (text == "false" || text == "0") return false;
  return std::nullopt;
}

bool near(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return std::fabs(a - b) <= 1e-6 * std::max({1.0, std::fabs(a), std::fabs(b)});
}

// Whether `element` matches `value` for contains/lacks.
bool element_matches(const nlohmann::ordered_json& element, const std::string& value) {
  if (element.is_string()) return element.get_ref<const std::string&>().find(value) != std::string::npos;
  if (element.is_boolean()) return parse_bool(value) == element.get<bool>();
  if (element.is_number()) {
    const auto number = parse_number(value);
    return number && near(element.get<double>(), *number);
  }
  return false;
}

PredicateVerdict broken(std::string detail) {
  return PredicateVerdict{false, true, std::move(detail)};
}

}  // namespace

Expected<Predicate> parse_predicate(std::string_view text) {
  Predicate out;
  out.text = std::string(trim(text));
  std::string_view rest = text;
  const std::string_view path = next_word(rest);
  if (path.empty())
    return make_error(ErrorCode::kInvalidArgument, "empty condition: write '<field> <operator> [value]'");
  auto parts = parse_path(path);
  if (!parts) return std::move(parts).error();
  out.path = std::move(*parts);
  const std::string_view op = next_word(rest);
  const auto known = std::find_if(std::begin(kOperators), std::end(kOperators),
                                  [&](const OperatorName& o) { return o.text == op; });
  if (known == std::end(kOperators)) {
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("condition '{}': {} (operators: ==, !=, <, <=, >, >=, contains, lacks, empty, "
                    "not_empty)",
                    out.text, op.empty() ? "no operator" : fmt::format("unknown operator '{}'", op)));
  }
  out.op = known->op;
  out.value = unquote(rest);
  if (known->takes_value && trim(rest).empty()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("condition '{}': '{}' needs a value to compare with", out.text, op));
  }
  if (!known->takes_value && !trim(rest).empty()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("condition '{}': '{}' takes no value", out.text, op));
  }
  return out;
}

PredicateVerdict evaluate(const Predicate& predicate, const nlohmann::ordered_json& state) {
  std::string why;
  const nlohmann::ordered_json* field = resolve(predicate.path, state, why);
  if (field == nullptr) return broken(std::move(why));
  const std::string shown = safe_dump(*field);
  const std::string path = predicate.text.substr(0, predicate.text.find_first_of(" \t"));
  const auto verdict = [&](bool holds) {
    return PredicateVerdict{holds, false, fmt::format("{} is {}", path, shown)};
  };
  switch (predicate.op) {
    case Operator::kEmpty:
    case Operator::kNotEmpty: {
      if (!field->is_array() && !field->is_string())
        return broken(fmt::format("{} is {}, not a list or string", path, shown));
      const bool empty =
          field->empty() || (field->is_string() && field->get_ref<const std::string&>().empty());
      return verdict(predicate.op == Operator::kEmpty ? empty : !empty);
    }
    case Operator::kContains:
    case Operator::kLacks: {
      bool found = false;
      if (field->is_array()) {
        found = std::any_of(field->begin(), field->end(),
                            [&](const auto& element) { return element_matches(element, predicate.value); });
      } else if (field->is_string()) {
        found = field->get_ref<const std::string&>().find(predicate.value) != std::string::npos;
      } else {
        return broken(fmt::format("{} is {}, not a list or string", path, shown));
      }
      return verdict(predicate.op == Operator::kContains ? found : !found);
    }
    default:
      break;
  }
  const bool equality = predicate.op == Operator::kEq || predicate.op == Operator::kNe;
  if (field->is_boolean()) {
    const auto wanted = parse_bool(predicate.value);
    if (!equality || !wanted) {
      return broken(fmt::format("{} is a boolean: compare it with == or != and true or false", path));
    }
    return verdict((field->get<bool>() == *wanted) == (predicate.op == Operator::kEq));
  }
  if (field->is_number() || field->is_null()) {  // null: a NaN float
    const auto wanted = parse_number(predicate.value);
    if (!wanted) return broken(fmt::format("{} is a number; '{}' is not", path, predicate.value));
    const double value = field->is_null() ? std::nan("") : field->get<double>();
    switch (predicate.op) {
      case Operator::kEq:
        return verdict(near(value, *wanted));
      case Operator::kNe:
        return verdict(!near(value, *wanted));
      case Operator::kLt:
        return verdict(value < *wanted && !near(value, *wanted));
      case Operator::kLe:
        return verdict(value <= *wanted || near(value, *wanted));
      case Operator::kGt:
        return verdict(value > *wanted && !near(value, *wanted));
      case Operator::kGe:
        return verdict(value >= *wanted || near(value, *wanted));
      default:
        break;
    }
  }
  if (field->is_string()) {
    if (!equality)
      return broken(fmt::format("{} is a string: compare it with ==, !=, contains or lacks", path));
    return verdict((field->get_ref<const std::string&>() == predicate.value) ==
                   (predicate.op == Operator::kEq));
  }
  return broken(fmt::format("{} is {}: a struct or list cannot be compared with '{}'", path, shown,
                            predicate.text.substr(path.size())));
}

}  // namespace hubrt::hubctl
