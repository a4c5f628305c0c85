#include <algorithm>

#include <fmt/format.h>

#include "hubrt/mcap/compression.h"
#include "hubrt/mcap/summary.h"

namespace hubrt::mcap {
namespace {

Error protocol(const ByteSource& source, const std::string& why) {
  return make_error(ErrorCode::kProtocol, fmt::format("{}: {}", source.name(), why));
}

// Reads [offset, offset + length) whole. Errors: the range is outside the file or too large.
Expected<std::vector<std::uint8_t>> read_range(ByteSource& source, std::uint64_t offset, std::uint64_t length,
                                               const ReaderOptions& options, const char* what) {
  if (offset > source.size() || length > source.size() - offset)
    return protocol(source,
                    fmt::format("{} at byte {} ({} bytes) lies beyond the file's end", what, offset, length));
  if (length > options.max_record_bytes)
    return protocol(source, fmt::format("{} of {} bytes, more than the {} allowed", what, length,
                                        options.max_record_bytes));
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(length));
  auto got = source.read_at(offset, bytes);
  if (!got) return std::move(got).error();
  if (*got != bytes.size())
    return protocol(source, fmt::format("{} at byte {} could not be read whole", what, offset));
  return bytes;
}

template <class T, class Parse>
Expected<T> parse_as(const ByteSource& source, Parse parse, Bytes content) {
  auto parsed = parse(content);
  if (!parsed) return protocol(source, parsed.error().message);
  return std::move(*parsed);
}

}  // namespace

Expected<Summary> read_summary(ByteSource& source, const ReaderOptions& options) {
  constexpr std::uint64_t kFooterRecord = kRecordPrefixBytes + kFooterContentBytes;
  const std::uint64_t size = source.size();
  if (size < 2 * kMagic.size() + kFooterRecord)
    return protocol(source, "too short for an MCAP file with a Footer (cut off?)");
  const std::uint64_t footer_at = size - kMagic.size() - kFooterRecord;
  auto tail = read_range(source, footer_at, kFooterRecord + kMagic.size(), options, "the Footer");
  if (!tail) return std::move(tail).error();
  if (!std::equal(kMagic.begin(), kMagic.end(), tail->end() - kMagic.size()))
    return protocol(source,
                    "no MCAP magic at the end: the file is cut off (hubctl record --recover rebuilds it)");
  if ((*tail)[0] != static_cast<std::uint8_t>(Opcode::kFooter))
    return protocol(source, "no Footer record before the final magic");
  Summary summary;
  auto footer =
      parse_as<Footer>(source, parse_footer, Bytes(*tail).subspan(kRecordPrefixBytes, kFooterContentBytes));
  if (!footer) return std::move(footer).error();
  summary.footer = *footer;
  if (footer->summary_start == 0) return summary;
  if (footer->summary_start > footer_at)
    return protocol(source,
                    fmt::format("the summary starts at byte {}, after the Footer", footer->summary_start));
  if (footer->summary_offset_start != 0 &&
      (footer->summary_offset_start < footer->summary_start || footer->summary_offset_start > footer_at))
    return protocol(source, "the summary offset section lies outside the summary");
  auto section =
      read_range(source, footer->summary_start, footer_at - footer->summary_start, options, "the summary");
  if (!section) return std::move(section).error();
  if (footer->summary_crc != 0) {
    // From the summary's start through the Footer's summary_offset_start field (spec, "Footer").
    const std::uint32_t crc = crc32(Bytes(*tail).first(kRecordPrefixBytes + 16), crc32(*section));
    if (crc != footer->summary_crc)
      return protocol(source,
                      fmt::format("summary CRC is {:08x}, the Footer says {:08x}", crc, footer->summary_crc));
  }
  RecordCursor cursor(*section);
  RecordView record;
  for (;;) {
    auto more = cursor.next(record);
    if (!more) return protocol(source, "summary: " + more.error().message);
    if (!*more) break;
    switch (static_cast<Opcode>(record.opcode)) {
      case Opcode::kSchema: {
        auto schema = parse_as<Schema>(source, parse_schema, record.content);
        if (!schema) return std::move(schema).error();
        summary.schemas[schema->id] = std::move(*schema);
        break;
      }
      case Opcode::kChannel: {
        auto channel = parse_as<Channel>(source, parse_channel, record.content);
        if (!channel) return std::move(channel).error();
        summary.channels[channel->id] = std::move(*channel);
        break;
      }
      case Opcode::kStatistics: {
        auto statistics = parse_as<Statistics>(source, parse_statistics, record.content);
        if (!statistics) return std::move(statistics).error();
        summary.statistics = std::move(*statistics);
        break;
      }
      case Opcode::kChunkIndex: {
        auto index = parse_as<ChunkIndex>(source, parse_chunk_index, record.content);
        if (!index) return std::move(index).error();
        summary.chunk_indexes.push_back(std::move(*index));
        break;
      }
      case Opcode::kSummaryOffset: {
        auto offset = parse_as<SummaryOffset>(source, parse_summary_offset, record.content);
        if (!offset) return std::move(offset).error();
        summary.summary_offsets.push_back(*offset);
        break;
      }
      default:  // attachment and metadata indexes, records of later versions
        break;
    }
  }
  return summary;
}

Expected<std::vector<std::uint8_t>> read_chunk_records(ByteSource& source, const ChunkIndex& index,
                                                       const ReaderOptions& options) {
  auto record = read_range(source, index.chunk_start_offset, index.chunk_length, options, "the chunk");
  if (!record) return std::move(record).error();
  RecordCursor cursor(*record);
  RecordView view;
  auto whole = cursor.next(view);
  if (!whole || !*whole || view.opcode != static_cast<std::uint8_t>(Opcode::kChunk) ||
      cursor.offset() != record->size())
    return protocol(source, fmt::format("no Chunk record of {} bytes at byte {}", index.chunk_length,
                                        index.chunk_start_offset));
  auto chunk = parse_as<ChunkView>(source, parse_chunk, view.content);
  if (!chunk) return std::move(chunk).error();
  if (chunk->compression != index.compression || chunk->records.size() != index.compressed_size ||
      chunk->uncompressed_size != index.uncompressed_size)
    return protocol(source,
                    fmt::format("the chunk at byte {} is not what its index says", index.chunk_start_offset));
  const auto compression = compression_from_name(chunk->compression);
  if (!compression) return protocol(source, fmt::format("unknown compression '{}'", chunk->compression));
  std::vector<std::uint8_t> records;
  if (auto out = decompress(*compression, chunk->records, chunk->uncompressed_size, options.max_chunk_bytes,
                            records);
      !out)
    return protocol(source,
                    fmt::format("chunk at byte {}: {}", index.chunk_start_offset, out.error().message));
  if (chunk->uncompressed_crc != 0 && crc32(records) != chunk->uncompressed_crc)
    return protocol(source, fmt::format("chunk at byte {}: CRC mismatch", index.chunk_start_offset));
  return records;
}

Expected<std::vector<MessageIndex>> read_message_indexes(ByteSource& source, const ChunkIndex& index,
                                                         const ReaderOptions& options) {
  const std::uint64_t start = index.chunk_start_offset + index.chunk_length;
  auto bytes = read_range(source, start, index.message_index_length, options, "the message indexes");
  if (!bytes) return std::move(bytes).error();
  std::vector<MessageIndex> indexes;
  RecordCursor cursor(*bytes);
  RecordView record;
  for (;;) {
    auto more = cursor.next(record);
    if (!more) return protocol(source, "message indexes: " + more.error().message);
    if (!*more) break;
    if (record.opcode != static_cast<std::uint8_t>(Opcode::kMessageIndex))
      return protocol(source, fmt::format("a record of opcode 0x{:02x} among the message indexes at byte {}",
                                          record.opcode, start + record.offset));
    auto parsed = parse_as<MessageIndex>(source, parse_message_index, record.content);
    if (!parsed) return std::move(parsed).error();
    const auto located = index.message_index_offsets.find(parsed->channel_id);
    if (located == index.message_index_offsets.end() || located->second != start + record.offset)
      return protocol(source, fmt::format("the message index of channel {} is not where the chunk index says",
                                          parsed->channel_id));
    indexes.push_back(std::move(*parsed));
  }
  return indexes;
}

}  // namespace hubrt::mcap
