#include "hubrt/hal/board/board_config.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

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

const BoardHttpDevice* BoardConfig::find_http(std::string_view device) const noexcept {
  return find_by(http, device,
                 [](const BoardHttpDevice& d) -> const std::string& { return d.config.device; });
}

Expected<std::string> load_http_authorization(const BoardHttpDevice& device) {
  if (device.authorization_file.empty()) return device.config.authorization;
  const std::string& path = device.authorization_file;
  std::ifstream in(path);
  if (!in) {
    const int error = errno;
    return make_error(
        error == EACCES ? ErrorCode::kPermissionDenied : ErrorCode::kNotFound,
        device.config.device + ": cannot read authorization_file " + path + ": " + std::strerror(error));
  }
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const bool control = std::any_of(line.begin(), line.end(),
                                   [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
  if (line.empty() || line.size() > 512 || control) {
    return make_error(ErrorCode::kInvalidArgument,
                      device.config.device + ": authorization_file " + path +
                          " must hold one line of at most 512 printable bytes (e.g. 'Basic <base64>')");
  }
  return line;
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
