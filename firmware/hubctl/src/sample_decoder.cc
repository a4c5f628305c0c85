#include "sample_decoder.h"

#include <cstdio>
#include <exception>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hubrt/msgs/json.h"

namespace hubrt::hubctl {

std::optional<nlohmann::ordered_json> SampleDecoder::decode(const msgs::TypeInfo& type,
                                                            const void* sample) noexcept {
  try {
    nlohmann::ordered_json value = msgs::to_json(type, sample);
    if (const auto bad = msgs::invalid_utf8_fields(type, sample); !bad.empty()) {
      report(fmt::format("a sample has text that is not valid UTF-8 in {} (shown with \\xHH escapes)",
                         fmt::join(bad, ", ")));
    }
    return value;
  } catch (const std::exception& e) {
    report(fmt::format("a sample could not be decoded and is skipped: {}", e.what()));
  } catch (...) {
    report("a sample could not be decoded and is skipped");
  }
  return std::nullopt;
}

void SampleDecoder::report(const std::string& what) noexcept {
  ++problems_;
  // Said once, then again only with a count every 100 samples: a hub that sends the same bad
  // text in every State must not bury the output it comes with.
  if (what == last_report_ && ++repeats_ % 100 != 0) return;
  try {
    if (what == last_report_) {
      fmt::print(stderr, "{}: {}: {} ({} samples so far)\n", tool_, topic_, what, repeats_ + 1);
    } else {
      fmt::print(stderr, "{}: {}: {}\n", tool_, topic_, what);
      last_report_ = what;
      repeats_ = 0;
    }
  } catch (...) {  // stderr gone or out of memory: nothing more useful to do than go on
  }
}

std::string safe_dump(const nlohmann::ordered_json& value, int indent) {
  return value.dump(indent, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

}  // namespace hubrt::hubctl
