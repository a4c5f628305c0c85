// Opening a chip and one of its lines with libgpiod v1, with errors that say what is wrong.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include <gpiod.h>

#include "hubrt/base/status.h"

namespace hubrt::hal::gpiod_detail {

struct ChipCloser {
  void operator()(gpiod_chip* chip) const noexcept { gpiod_chip_close(chip); }
};
using ChipHandle = std::unique_ptr<gpiod_chip, ChipCloser>;

// An open chip and one of its lines, requested or not. Releases the line (if requested) and then
// closes the chip when destroyed. Move-only.
class LineHandle {
 public:
  LineHandle(ChipHandle chip, gpiod_line* line, std::string description) noexcept;
  LineHandle(LineHandle&& other) noexcept;
  LineHandle& operator=(LineHandle&&) = delete;
  LineHandle(const LineHandle&) = delete;
  LineHandle& operator=(const LineHandle&) = delete;
  ~LineHandle();

  [[nodiscard]] gpiod_line* line() const noexcept { return line_; }
  [[nodiscard]] gpiod_chip* chip() const noexcept { return chip_.get(); }
  // "line 5 of gpiochip0 [pinctrl-bcm2711]", for messages.
  [[nodiscard]] const std::string& description() const noexcept { return description_; }

 private:
  ChipHandle chip_;   // declared first: closed after the line is released
  gpiod_line* line_;  // owned by chip_
  std::string description_;
};

// Opens `chip` (path, name or label) and looks up line `offset`, without requesting it.
// Errors as documented for open_gpiod_input; messages start with "<signal>: ".
Expected<LineHandle> find_line(std::string_view signal, const std::string& chip, unsigned offset);

// Requests the line with our consumer name. `request_type` is a GPIOD_LINE_REQUEST_* type, `flags`
// GPIOD_LINE_REQUEST_FLAG_* bits, `default_value` the logical level of an output.
// Errors: kBusy (naming the holder), kPermissionDenied, kInvalidArgument (flags refused), kIo.
Expected<void> request_line(const LineHandle& handle, std::string_view signal, int request_type, int flags,
                            int default_value);

// The error for a line request that failed with `err` (errno), as request_line reports it;
// `flags` goes into the message of a refused request.
Error request_error(const LineHandle& handle, std::string_view signal, int flags, int err);

}  // namespace hubrt::hal::gpiod_detail
