// Checks on a whole YAML document that yaml-cpp does not make: that the text is strict UTF-8,
// and that no mapping has the same key twice. Every YamlMap document passes both before anyone
// reads a value from it, so hub files, board files, scenarios and the station description
// share one rule and one message for each.
#pragma once

#include <string>
#include <string_view>

#include <yaml-cpp/yaml.h>

#include "hubrt/base/status.h"

namespace hubrt::config::detail {

// Errors: kInvalidArgument "<name>:<line>:<column>: not valid UTF-8 (byte 0xC0) ...", the line
// and column (in characters) of the first byte of the first ill-formed sequence.
Expected<void> check_utf8(std::string_view text, const std::string& name);

// yaml-cpp keeps every entry of a mapping that repeats a key, and a look-up (node["rate_hz"])
// finds only the first: `rate_hz: 10` followed by `rate_hz: 500` would silently run at 10 Hz.
// Errors: kInvalidArgument "<name>:<line>:<column>: <path>: declared twice (first at line N)"
// for the first repeated key anywhere in the document (mappings inside lists included).
Expected<void> check_unique_keys(const YAML::Node& root, const std::string& name);

}  // namespace hubrt::config::detail
