// Decoding the tool-ID lines: each tool closes its own line when it sits on the changer.
#pragma once

#include <cstddef>
#include <span>

namespace hubrt::rsp_ecu {

struct ToolId {
  enum class Kind : unsigned char {
    kNone,       // no line set: no tool on the changer
    kOne,        // exactly one line set: `index` is the tool
    kUndefined,  // more than one line set, or a line that could not be read
  };
  Kind kind = Kind::kUndefined;
  std::size_t index = 0;

  [[nodiscard]] bool is_one() const noexcept { return kind == Kind::kOne; }
};

// One tool-ID line as read this cycle.
struct ToolLineReading {
  bool readable = false;
  bool set = false;
};

// The tool on the changer. An unreadable line makes the answer undefined, never "none": a line we
// cannot see might be the tool that is there. Pure; never allocates.
[[nodiscard]] inline ToolId decode_tool_id(std::span<const ToolLineReading> lines) noexcept {
  ToolId out{ToolId::Kind::kNone, 0};
  std::size_t set = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!lines[i].readable) return ToolId{ToolId::Kind::kUndefined, 0};
    if (lines[i].set) {
      ++set;
      out.index = i;
    }
  }
  if (set == 1) out.kind = ToolId::Kind::kOne;
  if (set > 1) out = ToolId{ToolId::Kind::kUndefined, 0};
  return out;
}

}  // namespace hubrt::rsp_ecu
