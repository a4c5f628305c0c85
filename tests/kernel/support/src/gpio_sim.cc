#include "hubrt/kernel_test/gpio_sim.h"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <string_view>
#include <system_error>
#include <thread>

namespace hubrt::kernel_test {
namespace {

std::string errno_text(int error) {
  return std::generic_category().message(error);
}

Expected<std::string> sim_file(const GpioSimChip& chip, unsigned offset, std::string_view attribute) {
  if (offset >= chip.num_lines) {
    return make_error(ErrorCode::kOutOfRange, "gpio-sim " + chip.name + ": line " + std::to_string(offset) +
                                                  " past its " + std::to_string(chip.num_lines) + " lines");
  }
  return chip.sysfs_dir + "/sim_gpio" + std::to_string(offset) + "/" + std::string(attribute);
}

}  // namespace

Expected<void> set_pull(const GpioSimChip& chip, unsigned offset, Pull pull) {
  auto path = sim_file(chip, offset, "pull");
  if (!path) return std::move(path).error();
  const std::string_view text = pull == Pull::kUp ? "pull-up" : "pull-down";
  const int fd = ::open(path->c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return make_error(ErrorCode::kIo, *path + ": open: " + errno_text(errno));
  const ssize_t written = ::write(fd, text.data(), text.size());
  const int write_errno = errno;
  ::close(fd);
  if (written != static_cast<ssize_t>(text.size())) {
    return make_error(ErrorCode::kIo,
                      *path + ": write '" + std::string(text) + "': " + errno_text(write_errno));
  }
  return {};
}

Expected<int> read_value(const GpioSimChip& chip, unsigned offset) {
  auto path = sim_file(chip, offset, "value");
  if (!path) return std::move(path).error();
  const int fd = ::open(path->c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return make_error(ErrorCode::kIo, *path + ": open: " + errno_text(errno));
  std::array<char, 8> buffer{};
  const ssize_t got = ::read(fd, buffer.data(), buffer.size());
  const int read_errno = errno;
  ::close(fd);
  if (got < 0) return make_error(ErrorCode::kIo, *path + ": read: " + errno_text(read_errno));
  const std::string_view text(buffer.data(), static_cast<std::size_t>(got));
  if (text == "0\n") return 0;
  if (text == "1\n") return 1;
  return make_error(ErrorCode::kProtocol, *path + ": expected 0 or 1, got '" + std::string(text) + "'");
}

Expected<void> wait_for_value(const GpioSimChip& chip, unsigned offset, int expected,
                              std::chrono::milliseconds timeout) {
  // Polling interval: short against the timeouts tests use, long enough not to hog a core.
  constexpr auto kPollInterval = std::chrono::milliseconds(5);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    auto value = read_value(chip, offset);
    if (!value) return std::move(value).error();
    if (*value == expected) return {};
    if (std::chrono::steady_clock::now() >= deadline) {
      return make_error(ErrorCode::kTimeout, "gpio-sim " + chip.name + " line " + std::to_string(offset) +
                                                 ": still " + std::to_string(*value) + " after " +
                                                 std::to_string(timeout.count()) + " ms, expected " +
                                                 std::to_string(expected));
    }
    std::this_thread::sleep_for(kPollInterval);
  }
}

}  // namespace hubrt::kernel_test
