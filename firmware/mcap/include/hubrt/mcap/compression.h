// Chunk compression as MCAP names it (spec registry.md, "Compression formats"): "" (none), "zstd"
// (a Zstandard frame) and "lz4" (an LZ4 frame), on Debian's libzstd and liblz4.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/mcap/records.h"

namespace hubrt::mcap {

enum class Compression : std::uint8_t { kNone, kZstd, kLz4 };

// The name a Chunk record carries: "", "zstd", "lz4".
std::string_view compression_name(Compression compression) noexcept;
// The compression a name stands for; nullopt for one this library does not read.
std::optional<Compression> compression_from_name(std::string_view name) noexcept;

// Compresses into `out` (replacing its contents); keeps its library context between calls so
// that a writer compressing chunk after chunk does not set it up each time.
// Not thread-safe: one per writer.
class Compressor {
 public:
  explicit Compressor(Compression compression);
  ~Compressor();
  Compressor(Compressor&&) noexcept;
  Compressor& operator=(Compressor&&) noexcept;
  Compressor(const Compressor&) = delete;
  Compressor& operator=(const Compressor&) = delete;

  // Errors: kInternal with the library's message (out of memory).
  Expected<void> compress(Bytes in, std::vector<std::uint8_t>& out);
  [[nodiscard]] Compression compression() const noexcept { return compression_; }

 private:
  struct Contexts;
  Compression compression_;
  std::unique_ptr<Contexts> contexts_;
};

// Decompresses `in` into `out`, which must come out exactly `uncompressed_size` bytes long (the
// Chunk's own field): the size is checked before anything is allocated, against `max_size`.
// Errors: kProtocol for data that does not decompress, or to another size ("zstd: ..."),
// kOutOfRange when uncompressed_size exceeds max_size. Thread-safe.
Expected<void> decompress(Compression compression, Bytes in, std::uint64_t uncompressed_size,
                          std::uint64_t max_size, std::vector<std::uint8_t>& out);

}  // namespace hubrt::mcap
