#include "hubrt/hal/board/board_config.h"

#include <algorithm>

namespace hubrt::hal {
namespace {

template <class T, class Key>
const T* find_by(const std::vector<T>& items, std::string_view name, Key key) noexcept {
  const auto it = std::find_if(items.begin(), items.end(), [&](const T& item) { return key(item) == name; });
  return it == items.end() ? nullptr : &*it;
}

}  // namespace

const BoardInput* BoardConfig::find_input(std::string_view signal) const noexcept {
  return find_by(inputs, signal, [](const BoardInput& i) -> const std::string& { return i.config.signal; });
}

const BoardOutput* BoardConfig::find_output(std::string_view signal) const noexcept {
  return find_by(outputs, signal, [](const BoardOutput& o) -> const std::string& { return o.config.signal; });
}

const BoardCanBus* BoardConfig::find_can(std::string_view bus) const noexcept {
  return find_by(can, bus, [](const BoardCanBus& b) -> const std::string& { return b.config.bus; });
}

const BoardModbusDevice* BoardConfig::find_modbus(std::string_view device) const noexcept {
  return find_by(modbus, device,
                 [](const BoardModbusDevice& d) -> const std::string& { return d.config.device; });
}

const BoardBadgeReader* BoardConfig::find_badge_reader(std::string_view reader) const noexcept {
  return find_by(badge_readers, reader,
                 [](const BoardBadgeReader& r) -> const std::string& { return r.config.reader; });
}

const BoardGpioChip* BoardConfig::find_chip(std::string_view alias) const noexcept {
  return find_by(chips, alias, [](const BoardGpioChip& c) -> const std::string& { return c.alias; });
}

bool BoardConfig::wired_for(std::string_view hub) const noexcept {
  return std::find(hubs.begin(), hubs.end(), hub) != hubs.end();
}

}  // namespace hubrt::hal
