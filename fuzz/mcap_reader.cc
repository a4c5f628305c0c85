// An MCAP file from anywhere — a recording copied off a station, a black box, a file someone sends
// — through every reader hubctl uses: the linear reader of play, echo --from and record --recover
// (records, chunks decompressed with zstd or lz4, CRCs), then the summary reader and, through each
// chunk index, the chunk and its message indexes. Input: the file's bytes.
#include <cstddef>
#include <cstdint>

#include "hubrt/mcap/linear_reader.h"
#include "hubrt/mcap/summary.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hubrt::mcap::Bytes bytes(data, size);
  // Small limits, so that a claimed size the fuzzer makes up costs little; the code paths are the
  // same as with the defaults.
  hubrt::mcap::ReaderOptions options;
  options.max_record_bytes = 1 << 20;
  options.max_chunk_bytes = 4 << 20;
  auto reader = hubrt::mcap::LinearReader::open(hubrt::mcap::memory_source(bytes), options);
  if (reader) {
    std::uint64_t sum = 0;
    while (auto message = reader->next()) {
      // What a consumer does with a message: find its channel and schema, read its bytes.
      const auto& channel = reader->channels().at(message->channel_id);
      if (channel.schema_id != 0) sum += reader->schemas().at(channel.schema_id).data.size();
      for (const std::uint8_t b : message->data) sum += b;
    }
    (void)sum;
  }
  auto source = hubrt::mcap::memory_source(bytes);
  auto summary = hubrt::mcap::read_summary(*source, options);
  if (!summary) return 0;
  std::size_t chunks = 0;
  for (const auto& index : summary->chunk_indexes) {
    if (++chunks > 16) break;
    (void)hubrt::mcap::read_chunk_records(*source, index, options);
    (void)hubrt::mcap::read_message_indexes(*source, index, options);
  }
  return 0;
}
