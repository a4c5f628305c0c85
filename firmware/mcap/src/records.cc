// Each record's fields in the order of the MCAP specification's tables (website/docs/spec/index.md,
// "Records"), written and read through detail::ByteWriter / ByteReader.
#include "hubrt/mcap/records.h"

#include <zlib.h>

#include <fmt/format.h>

#include "byte_io.h"

namespace hubrt::mcap {
namespace {

using detail::ByteReader;
using detail::ByteWriter;

// <opcode><uint64 content length><content>, the length filled in once the content is written.
template <class WriteContent>
std::size_t framed(std::vector<std::uint8_t>& out, Opcode opcode, WriteContent&& write_content) {
  const std::size_t start = out.size();
  out.push_back(static_cast<std::uint8_t>(opcode));
  const std::size_t length_at = out.size();
  out.resize(out.size() + 8);
  ByteWriter writer(out);
  write_content(writer);
  const std::uint64_t length = out.size() - length_at - 8;
  for (int i = 0; i < 8; ++i)
    out[length_at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(length >> (8 * i));
  return out.size() - start;
}

// Map<uint16, uint64>: a uint32 byte length, then key/value pairs.
void write_u16_u64_map(ByteWriter& w, const std::map<std::uint16_t, std::uint64_t>& map) {
  w.u32(static_cast<std::uint32_t>(map.size() * 10));
  for (const auto& [key, value] : map) {
    w.u16(key);
    w.u64(value);
  }
}

bool read_u16_u64_map(ByteReader& r, std::map<std::uint16_t, std::uint64_t>& map, const char* field) {
  Bytes entries;
  if (!r.sized_bytes32(entries, field)) return false;
  ByteReader inner(entries, field);
  while (inner.remaining() > 0) {
    std::uint16_t key = 0;
    std::uint64_t value = 0;
    if (!inner.u16(key, field) || !inner.u64(value, field)) return false;
    map[key] = value;
  }
  return true;
}

template <class T>
Expected<T> done(bool ok, const ByteReader& reader, T value) {
  if (!ok) return reader.failure();
  return value;
}

}  // namespace

std::size_t append_record(std::vector<std::uint8_t>& out, const Header& record) {
  return framed(out, Opcode::kHeader, [&](ByteWriter& w) {
    w.string(record.profile);
    w.string(record.library);
  });
}

std::size_t append_record(std::vector<std::uint8_t>& out, const Footer& record) {
  return framed(out, Opcode::kFooter, [&](ByteWriter& w) {
    w.u64(record.summary_start);
    w.u64(record.summary_offset_start);
    w.u32(record.summary_crc);
  });
}

std::size_t append_record(std::vector<std::uint8_t>& out, const Schema& record) {
  return framed(out, Opcode::kSchema, [&](ByteWriter& w) {
    w.u16(record.id);
    w.string(record.name);
    w.string(record.encoding);
    w.string(record.data);  // uint32 length-prefixed bytes: the same layout as a String
  });
}

std::size_t append_record(std::vector<std::uint8_t>& out, const Channel& record) {
  return framed(out, Opcode::kChannel, [&](ByteWriter& w) {
    w.u16(record.id);
    w.u16(record.schema_id);
    w.string(record.topic);
    w.string(record.message_encoding);
    const std::size_t length_at = w.reserve_u32();
    const std::size_t start = w.size();
    for (const auto& [key, value] : record.metadata) {
      w.string(key);
      w.string(value);
    }
    w.fill_u32(length_at, static_cast<std::uint32_t>(w.size() - start));
  });
}

std::size_t message_record_size(std::size_t data_bytes) noexcept {
  return kRecordPrefixBytes + 2 + 4 + 8 + 8 + data_bytes;
}

std::size_t append_record(std::vector<std::uint8_t>& out, const Message& record) {
  return framed(out, Opcode::kMessage, [&](ByteWriter& w) {
    w.u16(record.channel_id);
    w.u32(record.sequence);
    w.u64(record.log_time);
    w.u64(record.publish_time);
    w.bytes(record.data);
  });
}

std::size_t append_record(std::vector<std::uint8_t>& out, const MessageIndex& record) {
  return framed(out, Opcode::kMessageIndex, [&](ByteWriter& w) {
    w.u16(record.channel_id);
    w.u32(static_cast<std::uint32_t>(record.records.size() * 16));
    for (const MessageIndexEntry& entry : record.records) {
      w.u64(entry.log_time);
      w.u64(entry.offset);
    }
  });
}

std::size_t append_record(std::vector<std::uint8_t>& out, const ChunkIndex& record) {
  return framed(out, Opcode::kChunkIndex, [&](ByteWriter& w) {
    w.u64(record.message_start_time);
    w.u64(record.message_end_time);
    w.u64(record.chunk_start_offset);
    w.u64(record.chunk_length);
    write_u16_u64_map(w, record.message_index_offsets);
    w.u64(record.message_index_length);
    w.string(record.compression);
    w.u64(record.compressed_size);
    w.u64(record.uncompressed_size);
  });
}

std::size_t append_record(std::vector<std::uint8_t>& out, const Statistics& record) {
  return framed(out, Opcode::kStatistics, [&](ByteWriter& w) {
    w.u64(record.message_count);
    w.u16(record.schema_count);
    w.u32(record.channel_count);
    w.u32(record.attachment_count);
    w.u32(record.metadata_count);
    w.u32(record.chunk_count);
    w.u64(record.message_start_time);
    w.u64(record.message_end_time);
    write_u16_u64_map(w, record.channel_message_counts);
  });
}

std::size_t append_record(std::vector<std::uint8_t>& out, const SummaryOffset& record) {
  return framed(out, Opcode::kSummaryOffset, [&](ByteWriter& w) {
    w.u8(static_cast<std::uint8_t>(record.group_opcode));
    w.u64(record.group_start);
    w.u64(record.group_length);
  });
}

std::size_t append_record(std::vector<std::uint8_t>& out, const DataEnd& record) {
  return framed(out, Opcode::kDataEnd, [&](ByteWriter& w) { w.u32(record.data_section_crc); });
}

std::vector<std::uint8_t> chunk_record_head(const ChunkView& chunk) {
  std::vector<std::uint8_t> out;
  ByteWriter w(out);
  w.u8(static_cast<std::uint8_t>(Opcode::kChunk));
  const std::uint64_t content = 8 + 8 + 8 + 4 + 4 + chunk.compression.size() + 8 + chunk.records.size();
  w.u64(content);
  w.u64(chunk.message_start_time);
  w.u64(chunk.message_end_time);
  w.u64(chunk.uncompressed_size);
  w.u32(chunk.uncompressed_crc);
  w.string(chunk.compression);
  w.u64(chunk.records.size());
  return out;
}

Expected<Header> parse_header(Bytes content) {
  ByteReader r(content, "Header");
  Header h;
  const bool ok = r.string(h.profile, "profile") && r.string(h.library, "library");
  return done(ok, r, std::move(h));
}

Expected<Footer> parse_footer(Bytes content) {
  ByteReader r(content, "Footer");
  Footer f;
  const bool ok = r.u64(f.summary_start, "summary_start") &&
                  r.u64(f.summary_offset_start, "summary_offset_start") &&
                  r.u32(f.summary_crc, "summary_crc");
  return done(ok, r, f);
}

Expected<Schema> parse_schema(Bytes content) {
  ByteReader r(content, "Schema");
  Schema s;
  Bytes data;
  const bool ok = r.u16(s.id, "id") && r.string(s.name, "name") && r.string(s.encoding, "encoding") &&
                  r.sized_bytes32(data, "data");
  if (ok) s.data.assign(data.begin(), data.end());
  return done(ok, r, std::move(s));
}

Expected<Channel> parse_channel(Bytes content) {
  ByteReader r(content, "Channel");
  Channel c;
  Bytes entries;
  bool ok = r.u16(c.id, "id") && r.u16(c.schema_id, "schema_id") && r.string(c.topic, "topic") &&
            r.string(c.message_encoding, "message_encoding") && r.sized_bytes32(entries, "metadata");
  if (!ok) return r.failure();
  ByteReader m(entries, "Channel metadata");
  while (m.remaining() > 0) {
    std::string key;
    std::string value;
    if (!m.string(key, "key") || !m.string(value, "value")) return m.failure();
    c.metadata[std::move(key)] = std::move(value);
  }
  return c;
}

Expected<Message> parse_message(Bytes content) {
  ByteReader r(content, "Message");
  Message m;
  const bool ok = r.u16(m.channel_id, "channel_id") && r.u32(m.sequence, "sequence") &&
                  r.u64(m.log_time, "log_time") && r.u64(m.publish_time, "publish_time");
  if (ok) m.data = r.rest();
  return done(ok, r, m);
}

Expected<ChunkView> parse_chunk(Bytes content) {
  ByteReader r(content, "Chunk");
  ChunkView c;
  const bool ok =
      r.u64(c.message_start_time, "message_start_time") && r.u64(c.message_end_time, "message_end_time") &&
      r.u64(c.uncompressed_size, "uncompressed_size") && r.u32(c.uncompressed_crc, "uncompressed_crc") &&
      r.string(c.compression, "compression") && r.sized_bytes64(c.records, "records");
  return done(ok, r, std::move(c));
}

Expected<MessageIndex> parse_message_index(Bytes content) {
  ByteReader r(content, "MessageIndex");
  MessageIndex index;
  Bytes entries;
  if (!r.u16(index.channel_id, "channel_id") || !r.sized_bytes32(entries, "records")) return r.failure();
  ByteReader e(entries, "MessageIndex records");
  while (e.remaining() > 0) {
    MessageIndexEntry entry;
    if (!e.u64(entry.log_time, "log_time") || !e.u64(entry.offset, "offset")) return e.failure();
    index.records.push_back(entry);
  }
  return index;
}

Expected<ChunkIndex> parse_chunk_index(Bytes content) {
  ByteReader r(content, "ChunkIndex");
  ChunkIndex c;
  const bool ok =
      r.u64(c.message_start_time, "message_start_time") && r.u64(c.message_end_time, "message_end_time") &&
      r.u64(c.chunk_start_offset, "chunk_start_offset") && r.u64(c.chunk_length, "chunk_length") &&
      read_u16_u64_map(r, c.message_index_offsets, "message_index_offsets") &&
      r.u64(c.message_index_length, "message_index_length") && r.string(c.compression, "compression") &&
      r.u64(c.compressed_size, "compressed_size") && r.u64(c.uncompressed_size, "uncompressed_size");
  return done(ok, r, std::move(c));
}

Expected<Statistics> parse_statistics(Bytes content) {
  ByteReader r(content, "Statistics");
  Statistics s;
  const bool ok = r.u64(s.message_count, "message_count") && r.u16(s.schema_count, "schema_count") &&
                  r.u32(s.channel_count, "channel_count") && r.u32(s.attachment_count, "attachment_count") &&
                  r.u32(s.metadata_count, "metadata_count") && r.u32(s.chunk_count, "chunk_count") &&
                  r.u64(s.message_start_time, "message_start_time") &&
                  r.u64(s.message_end_time, "message_end_time") &&
                  read_u16_u64_map(r, s.channel_message_counts, "channel_message_counts");
  return done(ok, r, std::move(s));
}

Expected<SummaryOffset> parse_summary_offset(Bytes content) {
  ByteReader r(content, "SummaryOffset");
  SummaryOffset s;
  std::uint8_t opcode = 0;
  const bool ok = r.u8(opcode, "group_opcode") && r.u64(s.group_start, "group_start") &&
                  r.u64(s.group_length, "group_length");
  s.group_opcode = static_cast<Opcode>(opcode);
  return done(ok, r, s);
}

Expected<DataEnd> parse_data_end(Bytes content) {
  ByteReader r(content, "DataEnd");
  DataEnd d;
  const bool ok = r.u32(d.data_section_crc, "data_section_crc");
  return done(ok, r, d);
}

Expected<bool> RecordCursor::next(RecordView& record) {
  if (offset_ == records_.size()) return false;
  const std::uint64_t left = records_.size() - offset_;
  if (left < kRecordPrefixBytes) {
    return make_error(
        ErrorCode::kProtocol,
        fmt::format("record at byte {}: {} byte(s) left, fewer than a record's prefix", offset_, left));
  }
  const std::uint8_t* at = records_.data() + offset_;
  const std::uint64_t length = detail::load_le(at + 1, 8);
  if (at[0] == 0)
    return make_error(ErrorCode::kProtocol, fmt::format("record at byte {}: opcode 0", offset_));
  if (length > left - kRecordPrefixBytes) {
    return make_error(ErrorCode::kProtocol,
                      fmt::format("record at byte {} (opcode 0x{:02x}): length {} beyond the "
                                  "{} byte(s) left",
                                  offset_, at[0], length, left - kRecordPrefixBytes));
  }
  record.opcode = at[0];
  record.offset = offset_;
  record.content = records_.subspan(static_cast<std::size_t>(offset_ + kRecordPrefixBytes),
                                    static_cast<std::size_t>(length));
  offset_ += kRecordPrefixBytes + length;
  return true;
}

std::uint32_t crc32(Bytes bytes, std::uint32_t crc) noexcept {
  // zlib's crc32 takes a uInt length: feed large spans in pieces.
  uLong value = crc;
  std::size_t done_bytes = 0;
  while (done_bytes < bytes.size()) {
    const std::size_t piece = std::min<std::size_t>(bytes.size() - done_bytes, 1U << 30);
    value = ::crc32(value, bytes.data() + done_bytes, static_cast<uInt>(piece));
    done_bytes += piece;
  }
  return static_cast<std::uint32_t>(value);
}

}  // namespace hubrt::mcap
