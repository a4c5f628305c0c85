// A board file (boards/*.yaml) as hubd --board reads it: YAML text through the board loader and
// its validator (hal/board).
#include <cstddef>
#include <cstdint>
#include <string>

#include "hubrt/hal/board/board_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  (void)hubrt::hal::load_board_string(text, "fuzz.yaml");
  return 0;
}
