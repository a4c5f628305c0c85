// A board file for the Dock ECU whose four slot sensors sit on lines of a gpio-sim chip that the
// kernel tier (or the test) made: hubd --backend linux then runs the real Dock ECU against it.
#pragma once

#include <array>
#include <string>

#include "hubrt/base/status.h"
#include "hubrt/kernel_test/environment.h"

namespace hubrt::kernel_test {

// One slot of hubs/dock_ecu/dock_ecu.yaml and the chip line its sensor is wired to here.
struct DockSlotWiring {
  const char* slot;    // the name in the State, e.g. "smart_tool"
  const char* signal;  // the board input, e.g. "dock.slot.smart_tool"
  unsigned offset;     // line offset on the chip
};

// The Raspberry Pi's lines (boards/rpi4-dock-ecu.yaml), in the hub file's slot order, so the
// State's slot i is kDockSlots[i].
inline constexpr std::array<DockSlotWiring, 4> kDockSlots{{
    {"ladder_frame_tool", "dock.slot.ladder_frame_tool", 5},
    {"filter_tool", "dock.slot.filter_tool", 6},
    {"smart_tool", "dock.slot.smart_tool", 12},
    {"spare", "dock.slot.spare", 13},
}};

// The debounce window the board file gives every slot, as on the Pi board.
inline constexpr int kDockDebounceMs = 20;

// How the board file names the chip: by its character device or by its label (which survives
// the chip being removed and made again under another gpiochipN).
enum class ChipReference { kPath, kLabel };

// A board file written into `directory` (the guest's root is read-only; /tmp is not), removed
// again when this object goes away. Move-only. Not thread-safe: one owner.
class DockBoardFile {
 public:
  // Writes "<directory>/<board name>.yaml": gpio chip alias `sim` referring to `chip` as `how`
  // says, the four dock.slot.* inputs on the kDockSlots lines, active high, pull-down bias and
  // kDockDebounceMs of debounce. Errors: kOutOfRange if the chip has too few lines for them;
  // kIo naming the file if it cannot be written.
  static Expected<DockBoardFile> write(const GpioSimChip& chip, ChipReference how,
                                       const std::string& directory);

  DockBoardFile(DockBoardFile&& other) noexcept;
  DockBoardFile& operator=(DockBoardFile&& other) noexcept;
  DockBoardFile(const DockBoardFile&) = delete;
  DockBoardFile& operator=(const DockBoardFile&) = delete;
  ~DockBoardFile();

  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  // The YAML written, for failure messages.
  [[nodiscard]] const std::string& text() const noexcept { return text_; }

 private:
  DockBoardFile(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {}

  std::string path_;  // empty once moved from
  std::string text_;
};

}  // namespace hubrt::kernel_test
