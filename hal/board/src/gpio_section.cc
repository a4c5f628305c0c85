// gpio: chips, inputs, outputs.
#include <map>
#include <utility>

#include <fmt/format.h>

#include "board_parse.h"

namespace hubrt::hal::board_detail {
namespace {

constexpr std::int64_t kMaxLine = 511;
constexpr std::int64_t kMaxDebounceMs = 10'000;

std::string chip_aliases(const BoardConfig& board) {
  std::string out;
  for (const BoardGpioChip& chip : board.chips) out += (out.empty() ? "" : ", ") + chip.alias;
  return out;
}

Expected<BoardGpioChip> parse_chip(const std::string& alias, const YamlMap& map) {
  if (!valid_identifier(alias)) {
    return map.error(
        "not a valid chip name (lower-case letters, digits, '_' and '-', starting with a letter)");
  }
  if (auto ok = map.only_keys({"name", "label", "path"}); !ok) return std::move(ok).error();
  const int given = int{map.has("name")} + int{map.has("label")} + int{map.has("path")};
  if (given != 1) return map.error("give exactly one of name, label or path");
  BoardGpioChip chip;
  chip.alias = alias;
  chip.where = where(map);
  const std::string_view key = map.has("name") ? "name" : map.has("label") ? "label" : "path";
  auto selector = map.string(key);
  if (!selector) return std::move(selector).error();
  chip.selector = *selector;
  chip.kind = classify_gpio_chip(chip.selector);
  const std::string_view expected_key = to_string(chip.kind);
  if (key != expected_key) {
    if (key == "name") {
      return map.error_at(
          key, fmt::format("'{}' is not a kernel chip name (gpiochipN); use label: or path:", chip.selector));
    }
    return map.error_at(key, fmt::format("'{}' is a chip {}, not a {}; write {}: {}", chip.selector,
                                         expected_key, key, expected_key, chip.selector));
  }
  return chip;
}

Expected<void> parse_chips(const YamlMap& gpio, BoardConfig& board) {
  auto chips = gpio.named_maps("chips");
  if (!chips) return std::move(chips).error();
  if (chips->empty()) return gpio.error_at("chips", "declare at least one chip");
  for (const auto& [alias, map] : *chips) {
    auto chip = parse_chip(alias, map);
    if (!chip) return std::move(chip).error();
    for (const BoardGpioChip& other : board.chips) {
      if (other.selector == chip->selector) {
        return map.error(
            fmt::format("names the same chip as {}", declared_at("chip", other.alias, other.where)));
      }
    }
    board.chips.push_back(std::move(*chip));
  }
  return {};
}

// A line in use, for the "used twice" check.
struct LineUse {
  std::string kind;  // "input" / "output"
  std::string signal;
  SourceLocation where;
};
using LineUses = std::map<std::pair<std::string, unsigned>, LineUse>;

// Parses what inputs and outputs share: name, chip, line; records the line as used.
Expected<void> parse_wiring(const std::string& signal, const YamlMap& map, const char* kind,
                            BoardConfig& board, LineUses& uses, std::string& chip_alias,
                            std::string& selector, unsigned& line) {
  if (!valid_signal_name(signal)) {
    return map.error(
        "not a valid signal name (lower-case words of letters, digits and '_' separated by dots, e.g. "
        "dock.slot.smart_tool)");
  }
  if (const BoardInput* input = board.find_input(signal)) {
    return map.error(
        fmt::format("signal '{}' is already declared as an input (line {})", signal, input->where.line));
  }
  if (const BoardOutput* output = board.find_output(signal)) {
    return map.error(
        fmt::format("signal '{}' is already declared as an output (line {})", signal, output->where.line));
  }
  auto alias = map.string("chip");
  if (!alias) return std::move(alias).error();
  const BoardGpioChip* chip = board.find_chip(*alias);
  if (chip == nullptr) {
    return map.error_at(
        "chip", fmt::format("unknown chip '{}' (gpio.chips declares: {})", *alias, chip_aliases(board)));
  }
  auto offset = map.integer("line", 0, kMaxLine);
  if (!offset) return std::move(offset).error();
  chip_alias = chip->alias;
  selector = chip->selector;
  line = static_cast<unsigned>(*offset);
  const auto [used, inserted] = uses.emplace(std::pair{chip_alias, line}, LineUse{kind, signal, where(map)});
  if (!inserted) {
    return map.error_at("line",
                        fmt::format("line {} of chip '{}' is already used by {}", line, chip_alias,
                                    declared_at(used->second.kind, used->second.signal, used->second.where)));
  }
  return {};
}

Expected<Polarity> parse_polarity(const YamlMap& map) {
  auto polarity = map.choice_or("polarity", "active_high", {"active_high", "active_low"});
  if (!polarity) return std::move(polarity).error();
  return *polarity == "active_low" ? Polarity::kActiveLow : Polarity::kActiveHigh;
}

Expected<void> parse_input(const std::string& signal, const YamlMap& map, BoardConfig& board,
                           LineUses& uses) {
  if (auto ok = map.only_keys({"chip", "line", "polarity", "bias", "debounce_ms", "catch_pulses"}); !ok)
    return ok;
  BoardInput input;
  input.config.signal = signal;
  input.where = where(map);
  auto wired =
      parse_wiring(signal, map, "input", board, uses, input.chip_alias, input.config.chip, input.config.line);
  if (!wired) return wired;
  auto polarity = parse_polarity(map);
  if (!polarity) return std::move(polarity).error();
  input.config.polarity = *polarity;
  auto bias = map.choice_or("bias", "as_is", {"as_is", "disabled", "pull_up", "pull_down"});
  if (!bias) return std::move(bias).error();
  input.config.bias = *bias == "disabled"    ? Bias::kDisabled
                      : *bias == "pull_up"   ? Bias::kPullUp
                      : *bias == "pull_down" ? Bias::kPullDown
                                             : Bias::kAsIs;
  auto debounce = map.integer_or("debounce_ms", 0, 0, kMaxDebounceMs);
  if (!debounce) return std::move(debounce).error();
  input.config.debounce = std::chrono::milliseconds(*debounce);
  auto catch_pulses = map.boolean_or("catch_pulses", false);
  if (!catch_pulses) return std::move(catch_pulses).error();
  input.config.catch_pulses = *catch_pulses;
  if (input.config.catch_pulses && *debounce > 0) {
    return map.error_at(
        "catch_pulses",
        "cannot be combined with debounce_ms: debouncing removes the one-read pulses it catches");
  }
  board.inputs.push_back(std::move(input));
  return {};
}

Expected<void> parse_output(const std::string& signal, const YamlMap& map, BoardConfig& board,
                            LineUses& uses) {
  if (auto ok = map.only_keys({"chip", "line", "polarity", "initial", "safe"}); !ok) return ok;
  BoardOutput output;
  output.config.signal = signal;
  output.where = where(map);
  auto wired = parse_wiring(signal, map, "output", board, uses, output.chip_alias, output.config.chip,
                            output.config.line);
  if (!wired) return wired;
  auto polarity = parse_polarity(map);
  if (!polarity) return std::move(polarity).error();
  output.config.polarity = *polarity;
  // The safe level is what a fault or shutdown drives: it must be chosen, never defaulted.
  auto safe = map.boolean("safe");
  if (!safe) return std::move(safe).error();
  output.config.safe = *safe;
  auto initial = map.boolean_or("initial", *safe);
  if (!initial) return std::move(initial).error();
  output.config.initial = *initial;
  board.outputs.push_back(std::move(output));
  return {};
}

}  // namespace

Expected<void> parse_gpio(const YamlMap& gpio, BoardConfig& board) {
  if (auto ok = gpio.only_keys({"chips", "inputs", "outputs"}); !ok) return ok;
  if (auto chips = parse_chips(gpio, board); !chips) return chips;
  if (!gpio.has("inputs") && !gpio.has("outputs")) return gpio.error("declare inputs, outputs or both");
  LineUses uses;
  if (gpio.has("inputs")) {
    auto inputs = gpio.named_maps("inputs");
    if (!inputs) return std::move(inputs).error();
    for (const auto& [signal, map] : *inputs) {
      if (auto ok = parse_input(signal, map, board, uses); !ok) return ok;
    }
  }
  if (gpio.has("outputs")) {
    auto outputs = gpio.named_maps("outputs");
    if (!outputs) return std::move(outputs).error();
    for (const auto& [signal, map] : *outputs) {
      if (auto ok = parse_output(signal, map, board, uses); !ok) return ok;
    }
  }
  return {};
}

}  // namespace hubrt::hal::board_detail
