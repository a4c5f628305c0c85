#include "hubrt/kernel_test/environment.h"

#include <charconv>
#include <cstdlib>
#include <string_view>

namespace hubrt::kernel_test {
namespace {

std::optional<std::string> env(const char* name) {
  // The environment is only read here, never written, so getenv's result stays valid.
  const char* value = std::getenv(name);  // NOLINT(concurrency-mt-unsafe)
  if (value == nullptr || *value == '\0') return std::nullopt;
  return std::string(value);
}

std::optional<unsigned> parse_unsigned(std::string_view text) {
  unsigned value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace

bool in_kernel_tier() {
  return env("HUBRT_KERNEL_TIER") == "1";
}

std::optional<GpioSimChip> gpiosim_chip_from_env() {
  if (!in_kernel_tier()) return std::nullopt;
  auto name = env("HUBRT_GPIOSIM_CHIP");
  auto dev_path = env("HUBRT_GPIOSIM_DEV");
  auto sysfs_dir = env("HUBRT_GPIOSIM_SYSFS");
  auto label = env("HUBRT_GPIOSIM_LABEL");
  auto lines_text = env("HUBRT_GPIOSIM_LINES");
  if (!name || !dev_path || !sysfs_dir || !label || !lines_text) return std::nullopt;
  auto lines = parse_unsigned(*lines_text);
  if (!lines || *lines == 0) return std::nullopt;
  return GpioSimChip{*name, *dev_path, *sysfs_dir, *label, *lines};
}

std::optional<std::string> vcan_from_env() {
  if (!in_kernel_tier()) return std::nullopt;
  return env("HUBRT_VCAN");
}

}  // namespace hubrt::kernel_test
