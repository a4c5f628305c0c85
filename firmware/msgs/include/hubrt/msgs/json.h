// Samples of generated types to and from JSON, driven by their TypeInfo. For tools (hubctl echo
// and send, logs), not for the fixed-rate cycle: these allocate.
//
// Mapping: struct <-> object (fields in declaration order), sequence and array <-> array,
// bool <-> true/false, integers and octet <-> integers, float32/float64 <-> numbers (NaN and
// infinities become null, and null reads back as NaN), string <-> string (to JSON, a byte that is
// not part of well-formed UTF-8 is escaped as \xHH: JSON text is UTF-8, and a peer's string need
// not be; invalid_utf8_fields() names such fields).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hubrt/base/status.h"
#include "hubrt/msgs/type_info.h"

namespace hubrt::msgs {

// Field order is kept (ordered_json); converts implicitly to nlohmann::json if needed.
// A string that is not valid UTF-8 (a hostile or broken peer sent it) comes out with its bad
// bytes escaped as "\xED" (hubrt::append_escaped_utf8), so that the result can always be
// dumped; invalid_utf8_fields() says which fields that happened to.
// Precondition: `sample` points to a valid instance of `type` (null strings read as "").
// Allocates; never fails. Thread-safe for concurrent reads of the same sample.
nlohmann::ordered_json to_json(const TypeInfo& type, const void* sample);

// Dotted paths of the strings of `sample` that are not valid UTF-8 (RFC 3629), e.g.
// "error_list[0]", "echo.action"; empty for a clean sample. Allocates; thread-safe for reads.
std::vector<std::string> invalid_utf8_fields(const TypeInfo& type, const void* sample);

// Assigns the fields present in `value` (an object) to `sample`; absent fields keep their values,
// a sequence given is replaced whole. Strings and sequence buffers are allocated with
// dds_string_dup / dds_alloc (sequences with _release = true), and replaced ones freed, so that
// dds_sample_free(sample, desc, DDS_FREE_CONTENTS) or free_contents() releases everything.
// Precondition: the sample owns its strings and sequence buffers (zeroed, or filled by
// from_json/set_field/dds_read) — never a runtime sample that points into fixed buffers.
// Errors (the sample is left unchanged; the message names the field path):
//   kInvalidArgument  unknown field (with suggestions), wrong JSON type, string with a NUL byte,
//                     array of the wrong length;
//   kOutOfRange       a number outside its field's range, too many elements for a bounded sequence.
// Not thread-safe for the same sample.
Expected<void> from_json(const TypeInfo& type, const nlohmann::ordered_json& value, void* sample);

}  // namespace hubrt::msgs
