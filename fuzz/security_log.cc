// A Cyclone log line through the reader of DDS Security refusals (hubrt/dds/security_refusals.h):
// the message carries a peer's GUID and the security plugin's reason, which quotes the peer's
// certificate subject — text the peer chose. Input: the source file Cyclone names on the first
// line, the function on the second, the message after them.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hubrt/dds/security_refusals.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool installed = [] {
    hubrt::dds::count_security_refusals();
    return true;
  }();
  (void)installed;
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const auto first = input.find('\n');
  if (first == std::string_view::npos) return 0;
  const auto second = input.find('\n', first + 1);
  if (second == std::string_view::npos) return 0;
  const std::string_view file = input.substr(0, first);
  const std::string_view function = input.substr(first + 1, second - first - 1);
  const std::string_view message = input.substr(second + 1);
  (void)hubrt::dds::classify_security_log(file, function, message);
  (void)hubrt::dds::detail::observe_security_log(file, function, message);
  (void)hubrt::dds::last_security_refusal();
  return 0;
}
