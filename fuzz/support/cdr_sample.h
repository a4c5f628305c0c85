// Raw CDR bytes to a sample of a generated type through Cyclone's own deserialiser, the way a
// sample from the network reaches a reader: a serialized sample (4-byte XCDR1 header + payload) is
// turned into a serdata of the topic's sertype, which checks ("normalises") the payload, and the
// serdata is read into the C struct. What fails Cyclone's check never reaches the hub; what
// passes it is exactly what the hub's reader hands to the node.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <dds/dds.h>

#include "hubrt/dds/cdr_codec.h"
#include "hubrt/msgs/type_info.h"

namespace hubrt::fuzz {

// Cyclone's deserialisation of one generated type (dds::CdrCodec), with the harnesses' input
// format. Created once per type per process on an isolated participant (no peers, no multicast: it
// sends nothing and hears nothing). Not thread-safe (harnesses are single-threaded).
class CdrDecoder {
 public:
  // The decoder for `type` (a topic type: type.descriptor != nullptr). Aborts with a message
  // when Cyclone refuses to create the participant or topic: the harness cannot run then.
  static CdrDecoder& of(const msgs::TypeInfo& type);

  // Builds a serialized sample from fuzz input and deserialises it into `sample`, which must be
  // zeroed or filled by an earlier decode (free it with free_sample()). Input byte 0: bit 0
  // little (1) or big (0) endian, bits 1-2 the header's padding count (options); the rest is the
  // payload. Returns false when Cyclone rejects the bytes (sample left untouched).
  bool decode(std::span<const std::uint8_t> input, void* sample) const;

  // Frees what decode() allocated inside `sample` and zeroes it.
  void free_sample(void* sample) const noexcept;

  [[nodiscard]] const msgs::TypeInfo& type() const noexcept { return *type_; }

  // Input for decode() holding `sample` serialised little-endian by Cyclone: seeds for corpora.
  [[nodiscard]] std::vector<std::uint8_t> encode(const void* sample) const;

 private:
  CdrDecoder(const msgs::TypeInfo& type, dds::CdrCodec codec) : type_(&type), codec_(std::move(codec)) {}

  const msgs::TypeInfo* type_;
  dds::CdrCodec codec_;
};

}  // namespace hubrt::fuzz
