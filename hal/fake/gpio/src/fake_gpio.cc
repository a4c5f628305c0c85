#include "hubrt/hal/fake/fake_gpio.h"

#include <cassert>

#include <fmt/format.h>

#include "hubrt/hal/common/gpio_chip_selector.h"

#include "fake_line_device.h"

namespace hubrt::hal::fake {

FakeGpioChip& FakeGpio::add_chip(std::string name, unsigned num_lines, std::size_t history_capacity) {
  assert(chip(name) == nullptr && num_lines > 0);
  chips_.push_back(std::make_unique<FakeGpioChip>(*this, std::move(name), num_lines, history_capacity));
  return *chips_.back();
}

FakeGpioChip* FakeGpio::chip(std::string_view name) noexcept {
  for (const auto& chip : chips_) {
    if (chip->name() == name) return chip.get();
  }
  return nullptr;
}

std::vector<std::string> FakeGpio::chip_names() const {
  std::vector<std::string> names;
  for (const auto& chip : chips_) names.push_back(chip->name());
  return names;
}

void FakeGpio::advance() noexcept {
  if (advancing_) return;
  advancing_ = true;
  const Time t = now();
  for (const auto& simulator : simulators_) simulator->advance_to(t);
  advancing_ = false;
}

Expected<FakeGpioChip*> FakeGpio::find_line(std::string_view signal, const std::string& chip_name,
                                            unsigned line) {
  FakeGpioChip* chip = this->chip(chip_name);
  if (chip == nullptr || !chip->present()) {
    std::string present;
    for (const auto& c : chips_) {
      if (c->present()) present += fmt::format(" {} ({} lines),", c->name(), c->num_lines());
    }
    if (present.empty()) {
      present = "no GPIO chips present";
    } else {
      present.pop_back();
      present.insert(0, "chips present:");
    }
    return make_error(ErrorCode::kNotFound,
                      fmt::format("{}: GPIO chip with {} '{}' not found; {}", signal,
                                  to_string(classify_gpio_chip(chip_name)), chip_name, present));
  }
  if (chip->access_denied_) {
    return make_error(ErrorCode::kPermissionDenied,
                      fmt::format("{}: permission denied opening GPIO chip '{}'", signal, chip_name));
  }
  if (line >= chip->num_lines()) {
    return make_error(ErrorCode::kOutOfRange,
                      fmt::format("{}: line {} is beyond GPIO chip {}, which has {} lines (0..{})", signal,
                                  line, chip->name(), chip->num_lines(), chip->num_lines() - 1));
  }
  if (chip->lines_[line].use != FakeGpioChip::Use::kFree) {
    return make_error(ErrorCode::kBusy, fmt::format("{}: line {} of {} is busy, held by '{}'", signal, line,
                                                    chip->name(), kFakeGpioConsumer));
  }
  return chip;
}

Expected<std::unique_ptr<DigitalInput>> FakeGpio::open_input(const DigitalInputConfig& config) {
  advance();
  auto chip = find_line(config.signal, config.chip, config.line);
  if (!chip) return std::move(chip).error();
  return std::unique_ptr<DigitalInput>(std::make_unique<FakeDigitalInput>(*this, **chip, config));
}

Expected<std::unique_ptr<DigitalOutput>> FakeGpio::open_output(const DigitalOutputConfig& config) {
  advance();
  auto chip = find_line(config.signal, config.chip, config.line);
  if (!chip) return std::move(chip).error();
  return std::unique_ptr<DigitalOutput>(std::make_unique<FakeDigitalOutput>(*this, **chip, config));
}

}  // namespace hubrt::hal::fake
