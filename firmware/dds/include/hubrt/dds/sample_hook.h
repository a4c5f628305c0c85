// Seeing each sample a writer sends or a reader takes as the bytes on the wire, on the thread that
// writes or takes it: hubd's black box records its hub's commands and States this way, without a
// second serialisation and without another reader.
#pragma once

#include <cstdint>
#include <span>

#include "hubrt/base/time.h"

namespace hubrt::dds {

class SampleHook {
 public:
  virtual ~SampleHook() = default;
  // `serialized`: the encapsulation header and the payload, valid during the call only.
  // `source_time`: the writer's source timestamp for a taken sample; zero for a written one (it is
  // stamped as it leaves). Called on the cycle thread: must not block, allocate or throw.
  virtual void on_sample(std::span<const std::uint8_t> serialized, WallTime source_time) noexcept = 0;
};

}  // namespace hubrt::dds
