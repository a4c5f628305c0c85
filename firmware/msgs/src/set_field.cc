#include "hubrt/msgs/set_field.h"

#include <cctype>
#include <charconv>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "json_value.h"
#include "sample_access.h"

namespace hubrt::msgs {
namespace {

using detail::Json;
using detail::Scalar;

struct PathStep {
  std::string_view name;
  std::optional<std::size_t> index;
};

bool is_name_char(char c, bool first) {
  const auto u = static_cast<unsigned char>(c);
  return c == '_' || std::isalpha(u) != 0 || (!first && std::isdigit(u) != 0);
}

Error bad_path(std::string_view path, std::size_t pos, std::string_view expected) {
  return make_error(
      ErrorCode::kInvalidArgument,
      fmt::format("malformed field path '{}': expected {} at position {}", path, expected, pos + 1));
}

// name ( '[' digits ']' )? ( '.' name ( '[' digits ']' )? )*
Expected<std::vector<PathStep>> parse_path(std::string_view path) {
  std::vector<PathStep> steps;
  std::size_t pos = 0;
  while (true) {
    const std::size_t start = pos;
    while (pos < path.size() && is_name_char(path[pos], pos == start)) ++pos;
    if (pos == start) return bad_path(path, pos, "a field name");
    PathStep step{path.substr(start, pos - start), std::nullopt};
    if (pos < path.size() && path[pos] == '[') {
      const std::size_t digits = ++pos;
      while (pos < path.size() && std::isdigit(static_cast<unsigned char>(path[pos])) != 0) ++pos;
      std::size_t index = 0;
      const auto [end, ec] = std::from_chars(path.data() + digits, path.data() + pos, index);
      if (pos == digits || ec != std::errc() || end != path.data() + pos)
        return bad_path(path, digits, "an index");
      if (pos >= path.size() || path[pos] != ']') return bad_path(path, pos, "']'");
      ++pos;
      step.index = index;
    }
    steps.push_back(step);
    if (pos == path.size()) return steps;
    if (path[pos] != '.') return bad_path(path, pos, "'.' or '['");
    ++pos;
  }
}

// Where a value goes: the slot (whole field or element) and its address, or nullptr while only
// checking a path that runs through an element still to be appended.
struct Target {
  FieldInfo slot{};
  void* addr = nullptr;
  std::string path;
};

// Walks `steps` over `type`. With apply == false nothing changes (addresses inside elements to be
// appended are nullptr); with apply == true sequences indexed at their length grow by one.
Expected<Target> resolve(const TypeInfo& type, void* sample, const std::vector<PathStep>& steps, bool apply) {
  const TypeInfo* current = &type;
  void* addr = sample;
  std::string walked;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const PathStep& step = steps[i];
    walked += (walked.empty() ? "" : ".") + std::string(step.name);
    const FieldInfo* field = detail::find_field(*current, step.name);
    if (field == nullptr) return detail::unknown_field(*current, step.name, walked);
    void* field_addr = addr == nullptr ? nullptr : detail::field_address(addr, *field);
    Target target{*field, field_addr, walked};
    if (step.index) {
      const std::size_t index = *step.index;
      walked += fmt::format("[{}]", index);
      if (field->kind != FieldKind::kSequence && field->kind != FieldKind::kArray) {
        return make_error(
            ErrorCode::kInvalidArgument,
            fmt::format("{}: '{}' is a {}, not a sequence or array; it takes no index", walked, field->name,
                        detail::is_scalar(field->kind) || field->kind == FieldKind::kString
                            ? describe_type(*field)
                            : "struct " + describe_type(*field)));
      }
      const std::size_t count =
          field_addr == nullptr && field->kind == FieldKind::kSequence
              ? 0
              : (field->kind == FieldKind::kArray ? field->bound : detail::element_count(*field, field_addr));
      const bool append = field->kind == FieldKind::kSequence && index == count;
      if (index > count || (index == count && !append)) {
        return make_error(
            ErrorCode::kOutOfRange,
            field->kind == FieldKind::kArray
                ? fmt::format("{}: index {} is out of range for {} (0..{})", walked, index,
                              describe_type(*field), field->bound - 1)
                : fmt::format("{}: index {} is past the end of '{}' (length {}; index {} appends)", walked,
                              index, field->name, count, count));
      }
      if (append && field->bound != 0 && count >= field->bound) {
        return make_error(ErrorCode::kOutOfRange, fmt::format("{}: '{}' holds at most {} elements", walked,
                                                              field->name, field->bound));
      }
      if (apply && append) detail::resize_sequence(*field, field_addr, count + 1);
      const bool exists = field_addr != nullptr && (apply || !append);
      target = Target{detail::element_slot(*field),
                      exists ? detail::element_address(*field, field_addr, index) : nullptr, walked};
    }
    if (i + 1 == steps.size()) return target;
    if (target.slot.kind != FieldKind::kStruct) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{} is a {}, so it has no field '{}'", walked, describe_type(target.slot),
                                    steps[i + 1].name));
    }
    current = target.slot.nested;
    addr = target.addr;
  }
  return make_error(ErrorCode::kInvalidArgument, "empty field path");
}

Expected<Scalar> parse_integer(std::string_view text) {
  const bool negative = !text.empty() && text.front() == '-';
  std::string_view digits = negative ? text.substr(1) : text;
  int base = 10;
  if (digits.size() > 2 && digits[0] == '0' && (digits[1] == 'x' || digits[1] == 'X')) {
    digits.remove_prefix(2);
    base = 16;
  }
  std::uint64_t magnitude = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), magnitude, base);
  if (digits.empty() || ec == std::errc::invalid_argument || end != digits.data() + digits.size()) {
    return make_error(ErrorCode::kInvalidArgument, "");
  }
  constexpr std::uint64_t kMinMagnitude = std::uint64_t{1} << 63;  // |INT64_MIN|
  if (ec == std::errc::result_out_of_range || (negative && magnitude > kMinMagnitude)) {
    return make_error(ErrorCode::kOutOfRange, "");
  }
  if (!negative) return Scalar{magnitude};
  return Scalar{magnitude == kMinMagnitude ? INT64_MIN : -static_cast<std::int64_t>(magnitude)};
}

Expected<Scalar> scalar_from_text(FieldKind kind, std::string_view text, const std::string& path) {
  const auto invalid = [&](std::string_view expected) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: expected {}, got '{}'", path, expected, text));
  };
  Scalar value;
  if (kind == FieldKind::kBool) {
    if (text == "true" || text == "1") {
      value = true;
    } else if (text == "false" || text == "0") {
      value = false;
    } else {
      return invalid("true or false");
    }
  } else if (detail::is_integer(kind)) {
    auto parsed = parse_integer(text);
    if (!parsed) {
      if (parsed.error().code == ErrorCode::kOutOfRange) {
        return make_error(ErrorCode::kOutOfRange,
                          fmt::format("{}: {} is out of range for {} ({})", path, text, to_string(kind),
                                      detail::integer_range(kind)));
      }
      return invalid(fmt::format("an integer ({}: {})", to_string(kind), detail::integer_range(kind)));
    }
    value = *parsed;
  } else {
    double d = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), d);
    if (text.empty() || ec == std::errc::invalid_argument || end != text.data() + text.size()) {
      return invalid(fmt::format("a number ({})", to_string(kind)));
    }
    if (ec == std::errc::result_out_of_range) {
      return make_error(ErrorCode::kOutOfRange,
                        fmt::format("{}: {} is out of range for {}", path, text, to_string(kind)));
    }
    value = d;
  }
  if (auto problem = detail::range_problem(kind, value); !problem.empty()) {
    return make_error(ErrorCode::kOutOfRange, fmt::format("{}: {}", path, problem));
  }
  return value;
}

}  // namespace

Expected<void> set_field(const TypeInfo& type, void* sample, std::string_view path, std::string_view text) {
  auto steps = parse_path(path);
  if (!steps) return std::move(steps).error();
  auto checked = resolve(type, sample, *steps, /*apply=*/false);
  if (!checked) return std::move(checked).error();
  const FieldInfo& slot = checked->slot;

  // Parse the value completely before anything in the sample changes.
  std::optional<Scalar> scalar;
  Json json;
  if (detail::is_scalar(slot.kind)) {
    auto parsed = scalar_from_text(slot.kind, text, checked->path);
    if (!parsed) return std::move(parsed).error();
    scalar = *parsed;
  } else if (slot.kind == FieldKind::kString) {
    if (text.find('\0') != std::string_view::npos) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: strings cannot contain a NUL character", checked->path));
    }
    if (slot.string_bound != 0 && text.size() > slot.string_bound) {
      return make_error(ErrorCode::kOutOfRange,
                        fmt::format("{}: at most {} bytes ({}), got {}", checked->path, slot.string_bound,
                                    describe_type(slot), text.size()));
    }
  } else {
    json = Json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded()) {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: expected a JSON value for {}, got '{}'",
                                                                 checked->path, describe_type(slot), text));
    }
    if (auto ok = detail::check_slot_json(slot, json, checked->path); !ok) return ok;
  }

  auto target = resolve(type, sample, *steps, /*apply=*/true);
  if (!target) return std::move(target).error();  // cannot happen after the check above
  if (scalar) {
    detail::store_scalar(slot.kind, target->addr, *scalar);
  } else if (slot.kind == FieldKind::kString) {
    detail::store_string(slot, target->addr, text);
  } else {
    detail::assign_slot_json(slot, json, target->addr);
  }
  return {};
}

}  // namespace hubrt::msgs
