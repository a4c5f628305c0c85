// Where a reader gets its bytes: a file (read with pread, so a recording of any size is read a
// record at a time) or memory (tests, the fuzz harness).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "hubrt/base/status.h"
#include "hubrt/mcap/records.h"

namespace hubrt::mcap {

// Thread-safety: one thread at a time.
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  // Bytes in the source when it was opened.
  [[nodiscard]] virtual std::uint64_t size() const noexcept = 0;
  // Reads up to out.size() bytes at `offset`; returns how many (fewer only at the end).
  // Errors: kIo with errno's text.
  virtual Expected<std::size_t> read_at(std::uint64_t offset, std::span<std::uint8_t> out) = 0;
  // A name for messages: the file's path, "memory".
  [[nodiscard]] virtual const std::string& name() const noexcept = 0;
};

// Opens `path` for reading. Errors: kNotFound, kPermissionDenied, kIo (errno's text, the path).
Expected<std::unique_ptr<ByteSource>> open_file(const std::string& path);
// Reads `bytes`, which must outlive the source.
std::unique_ptr<ByteSource> memory_source(Bytes bytes);

// Limits on what a file can make a reader allocate: a record (a compressed chunk, say) or a
// chunk's records beyond these is refused as corrupt. Chunks of MCAP writers are about 1 MiB.
struct ReaderOptions {
  std::uint64_t max_record_bytes = std::uint64_t{256} << 20;
  std::uint64_t max_chunk_bytes = std::uint64_t{256} << 20;
};

}  // namespace hubrt::mcap
