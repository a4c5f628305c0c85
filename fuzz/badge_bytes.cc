// What an RFID reader sends (hal/common/badge_line.h): any bytes, with the time between them,
// through the BadgeLineAssembler every reader backend uses. Byte pairs: the byte, then the
// milliseconds since the previous one; '\r' ends a badge. Whatever comes in, a good read is 1 to
// 32 printable ASCII characters and a malformed one keeps no text.
#include <chrono>
#include <cstddef>
#include <cstdint>

#include "hubrt/hal/common/badge_line.h"

namespace {

void check(const hubrt::hal::BadgeRead& read) {
  if (read.malformed) {
    if (read.length != 0 || read.problem.empty()) __builtin_trap();
    return;
  }
  if (read.length == 0 || read.length > hubrt::hal::BadgeRead::kMaxLength) __builtin_trap();
  for (char c : read.text()) {
    if (c < 0x20 || c > 0x7E) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  hubrt::hal::BadgeLineAssembler line(std::chrono::milliseconds(500));
  hubrt::Time now{};
  hubrt::hal::BadgeRead read;
  for (std::size_t i = 0; i + 1 < size; i += 2) {
    now += std::chrono::milliseconds(data[i + 1]);
    if (line.expire(read, now)) check(read);
    const char c = static_cast<char>(data[i]);
    if (c == '\r') {
      if (line.end(read, now)) check(read);
    } else {
      line.add(c, now);
    }
  }
  return 0;
}
