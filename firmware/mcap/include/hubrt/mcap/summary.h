// Reading an MCAP file from its end: the Footer, the summary section (Schema and Channel copies,
// Statistics, ChunkIndex records) and, through a ChunkIndex, one chunk and its MessageIndex
// records — what a reader that seeks uses (MCAP spec, "Summary Section", "Footer"). Tests check
// with it that a written file's indexes and summary agree with its data.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/mcap/records.h"
#include "hubrt/mcap/source.h"

namespace hubrt::mcap {

struct Summary {
  Footer footer;
  std::map<std::uint16_t, Schema> schemas;
  std::map<std::uint16_t, Channel> channels;
  std::optional<Statistics> statistics;
  std::vector<ChunkIndex> chunk_indexes;
  std::vector<SummaryOffset> summary_offsets;
};

// Reads the trailing magic, the Footer and the summary it points to, checking the summary's CRC.
// Errors (kProtocol, naming the source): no trailing magic or Footer (a file cut off: read it with
// LinearReader, or mcap::recover it), a CRC mismatch, a record that does not parse, a summary
// larger than options.max_record_bytes. kIo from the source.
Expected<Summary> read_summary(ByteSource& source, const ReaderOptions& options = {});

// The decompressed records of the chunk `index` locates, checked against its CRC and sizes.
// Errors: kProtocol when the chunk is not where and what the index says.
Expected<std::vector<std::uint8_t>> read_chunk_records(ByteSource& source, const ChunkIndex& index,
                                                       const ReaderOptions& options = {});

// The MessageIndex records after the chunk `index` locates, in file order. Errors: kProtocol
// when they are not where the index says or do not parse.
Expected<std::vector<MessageIndex>> read_message_indexes(ByteSource& source, const ChunkIndex& index,
                                                         const ReaderOptions& options = {});

}  // namespace hubrt::mcap
