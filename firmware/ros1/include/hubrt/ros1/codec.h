// The ROS 1 wire format of any reflected message type (firmware/msgs type_info.h), without code
// per type: a bridged hub type needs no C++ of its own.
//
// ROS 1 serialisation (roscpp_serialization, serialization.h; wiki.ros.org/msg "Serialization"):
// fields in declaration order, no padding, little-endian; bool and (u)int8 one byte; string =
// uint32 byte count + bytes (no NUL); variable-length array = uint32 element count + elements;
// fixed-length array = elements only; time = uint32 secs + uint32 nsecs (the same 8 bytes as
// builtin_interfaces/Time's int32 sec + uint32 nanosec); a nested message = its fields.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/msgs/type_info.h"

namespace hubrt::ros1 {

// Why a ROS 1 message could not be taken in.
enum class DecodeProblem : std::uint8_t {
  kMalformed,  // truncated, trailing bytes, a count larger than the bytes that follow
  kOverBound,  // a string or sequence longer than its IDL bound: dropped, never cut
  kBadText,    // a string that is not strict UTF-8 or holds a NUL byte
};

struct DecodeError {
  DecodeProblem problem = DecodeProblem::kMalformed;
  std::string field;    // dotted path, e.g. "slots[3].name"; empty for the message as a whole
  std::string message;  // one sentence naming the field and what is wrong
};

// Appends the ROS 1 serialisation of `sample` (a `type` laid out by idlc) to `out`. Never fails:
// every reflected sample has a ROS 1 form. Allocates (the output). Thread-safe for distinct
// outputs.
void encode(const msgs::TypeInfo& type, const void* sample, std::vector<std::uint8_t>& out);

// Fills `sample` (type.size bytes, zeroed or previously filled by decode) from the ROS 1 bytes
// `wire`, which must be exactly one message. Bounded strings and sequences over their bound, text
// that is not strict UTF-8 or holds a NUL, truncation and trailing bytes are refused: the sample
// is then left zeroed (whatever was allocated is freed) and the error names the field. Element
// counts are checked against the bytes left before anything is allocated, so hostile counts cost
// nothing. On success the sample owns its unbounded strings and sequences: release them with
// msgs::free_contents(). Thread-safe for distinct samples.
std::optional<DecodeError> decode(const msgs::TypeInfo& type, std::span<const std::uint8_t> wire,
                                  void* sample);

}  // namespace hubrt::ros1
