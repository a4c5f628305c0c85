// Turning a received sample into JSON without ever stopping hubctl: whatever a hub or another
// peer sends — text that is not UTF-8, anything the decoder cannot take — is reported on stderr
// and the stream goes on with the next sample. Every command that receives samples (echo, watch,
// list, hz, conformance, play) decodes through this.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "hubrt/msgs/type_info.h"

namespace hubrt::hubctl {

// One per topic (it remembers what it reported, to say it once rather than per sample).
// Not thread-safe.
class SampleDecoder {
 public:
  // `tool`: the prefix of reports, e.g. "hubctl echo"; `topic`: the ROS topic name.
  SampleDecoder(std::string tool, std::string topic) : tool_(std::move(tool)), topic_(std::move(topic)) {}

  // The sample as JSON (msgs::to_json): strings that are not valid UTF-8 come out escaped
  // ("\xED") and are reported. nullopt when the sample could not be decoded at all (reported;
  // the caller skips it). Never throws.
  std::optional<nlohmann::ordered_json> decode(const msgs::TypeInfo& type, const void* sample) noexcept;

  // Samples reported so far (bad text or not decodable).
  [[nodiscard]] std::size_t problems() const noexcept { return problems_; }

 private:
  void report(const std::string& what) noexcept;

  std::string tool_;
  std::string topic_;
  std::string last_report_;
  std::size_t problems_ = 0;
  std::size_t repeats_ = 0;
};

// value.dump() that cannot throw: invalid UTF-8 (which decode() never produces, but a value may
// come from elsewhere) is replaced by U+FFFD instead of nlohmann's type_error 316.
std::string safe_dump(const nlohmann::ordered_json& value, int indent = -1);

}  // namespace hubrt::hubctl
