// Assigns one field of a sample from text, addressed by a dotted path: what `hubctl send TOPIC
// FIELD=VALUE...` does with each argument.
#pragma once

#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/msgs/type_info.h"

namespace hubrt::msgs {

// Path: names separated by '.', each optionally indexed: "echo.action", "error_list[0]",
// "slots[1].occupied". Index == length of a sequence appends one element (zero-initialised apart
// from what the rest of the path sets); arrays take indices below their length.
// Text: for bool "true"/"false"/"1"/"0"; for integers and octet a decimal or 0x-hex number; for
// floats a decimal number, "nan" or "inf"; for strings the text itself; for a whole struct,
// sequence or array a JSON value, as from_json takes it (e.g. slots=[{"name":"a"}]).
// Same ownership rules as from_json(). Errors (the sample is left unchanged):
//   kInvalidArgument  malformed path, unknown field (the message suggests the closest names and
//                     lists the fields of that struct), an index on a non-container, a value that
//                     does not parse as the field's type;
//   kOutOfRange       a value outside the field's range, an index past the end.
// Not thread-safe for the same sample.
Expected<void> set_field(const TypeInfo& type, void* sample, std::string_view path, std::string_view text);

}  // namespace hubrt::msgs
