#include "hubrt/mcap/linear_reader.h"

#include <algorithm>

#include <fmt/format.h>

#include "hubrt/mcap/compression.h"

#include "byte_io.h"

namespace hubrt::mcap {
Expected<LinearReader> LinearReader::open(std::unique_ptr<ByteSource> source, ReaderOptions options) {
  LinearReader reader(std::move(source), options);
  ByteSource& src = *reader.source_;
  std::array<std::uint8_t, kMagic.size() + kRecordPrefixBytes> start{};
  auto got = src.read_at(0, start);
  if (!got) return std::move(got).error();
  if (*got < kMagic.size() || !std::equal(kMagic.begin(), kMagic.end(), start.begin()))
    return make_error(ErrorCode::kProtocol,
                      fmt::format("{} is not an MCAP file (no MCAP magic)", src.name()));
  if (*got < start.size() || start[kMagic.size()] != static_cast<std::uint8_t>(Opcode::kHeader))
    return make_error(ErrorCode::kProtocol, fmt::format("{}: no Header record after the magic", src.name()));
  const std::uint64_t length = detail::load_le(start.data() + kMagic.size() + 1, 8);
  if (length > options.max_record_bytes || length > src.size() - start.size())
    return make_error(ErrorCode::kProtocol, fmt::format("{}: the Header record is cut short", src.name()));
  std::vector<std::uint8_t> content(static_cast<std::size_t>(length));
  auto got_header = src.read_at(start.size(), content);
  if (!got_header) return std::move(got_header).error();
  if (*got_header != content.size())
    return make_error(ErrorCode::kProtocol, fmt::format("{}: the Header record is cut short", src.name()));
  auto header = parse_header(content);
  if (!header) return make_error(ErrorCode::kProtocol, src.name() + ": " + header.error().message);
  reader.header_ = std::move(*header);
  reader.data_crc_ = crc32(content, crc32(start));
  reader.offset_ = start.size() + length;
  return reader;
}

void LinearReader::stop_at(StopReason reason, std::string message) {
  stop_.reason = reason;
  stop_.offset = offset_;
  stop_.message = std::move(message);
}

std::optional<Message> LinearReader::next() {
  for (;;) {
    if (next_pending_ < pending_.size()) return pending_[next_pending_++];
    pending_.clear();
    next_pending_ = 0;
    if (stop_.reason != StopReason::kReading) return std::nullopt;
    if (!read_record()) return std::nullopt;
  }
}

bool LinearReader::read_record() {
  ByteSource& src = *source_;
  std::array<std::uint8_t, kRecordPrefixBytes> prefix{};
  auto got = src.read_at(offset_, prefix);
  if (!got) {
    stop_at(StopReason::kCorrupt, got.error().message);
    return false;
  }
  if (*got == 0) {
    stop_at(StopReason::kTruncated,
            fmt::format("the file ends at byte {} after whole records, without the DataEnd "
                        "record and the summary (cut off while being written?)",
                        offset_));
    return false;
  }
  if (*got < prefix.size()) {
    stop_at(StopReason::kTruncated, fmt::format("the file ends inside the record at byte {}", offset_));
    return false;
  }
  const std::uint8_t opcode = prefix[0];
  const std::uint64_t length = detail::load_le(prefix.data() + 1, 8);
  if (opcode == 0) {
    stop_at(StopReason::kCorrupt, fmt::format("record at byte {} has opcode 0", offset_));
    return false;
  }
  if (length > src.size() - offset_ - prefix.size()) {
    stop_at(StopReason::kTruncated,
            fmt::format("the file ends inside the record at byte {} (opcode 0x{:02x}, {} "
                        "byte(s) of {} there)",
                        offset_, opcode, src.size() - offset_ - prefix.size(), length));
    return false;
  }
  if (length > options_.max_record_bytes) {
    stop_at(StopReason::kCorrupt,
            fmt::format("record at byte {} (opcode 0x{:02x}) of {} bytes, more than the {} "
                        "allowed",
                        offset_, opcode, length, options_.max_record_bytes));
    return false;
  }
  record_.resize(static_cast<std::size_t>(length));
  auto got_content = src.read_at(offset_ + prefix.size(), record_);
  if (!got_content || *got_content != record_.size()) {
    stop_at(StopReason::kTruncated, fmt::format("the record at byte {} could not be read whole", offset_));
    return false;
  }
  const auto bad = [&](const std::string& why) {
    stop_at(StopReason::kCorrupt, fmt::format("record at byte {}: {}", offset_, why));
    return false;
  };
  switch (static_cast<Opcode>(opcode)) {
    case Opcode::kDataEnd: {
      auto end = parse_data_end(record_);
      if (!end) return bad(end.error().message);
      if (end->data_section_crc != 0 && end->data_section_crc != data_crc_)
        return bad(fmt::format("DataEnd: the data section's CRC is {:08x}, the record says {:08x}", data_crc_,
                               end->data_section_crc));
      stop_at(StopReason::kDataEnd, "the end of the data section");
      return false;
    }
    case Opcode::kFooter:
      stop_at(StopReason::kDataEnd, "the Footer (no DataEnd record)");
      return false;
    case Opcode::kSchema: {
      auto schema = parse_schema(record_);
      if (!schema) return bad(schema.error().message);
      if (!keep_schema(*schema, schemas_)) return false;
      break;
    }
    case Opcode::kChannel: {
      auto channel = parse_channel(record_);
      if (!channel) return bad(channel.error().message);
      if (!keep_channel(*channel, channels_, schemas_)) return false;
      break;
    }
    case Opcode::kMessage: {
      auto message = parse_message(record_);
      if (!message) return bad(message.error().message);
      if (channels_.count(message->channel_id) == 0)
        return bad(fmt::format("Message on channel {}, which no Channel record before it defines",
                               message->channel_id));
      pending_.push_back(*message);
      break;
    }
    case Opcode::kChunk:
      if (!read_chunk(record_)) return false;
      break;
    default:  // indexes, attachments, metadata, private records: nothing a linear reader needs
      break;
  }
  data_crc_ = crc32(record_, crc32(prefix, data_crc_));
  offset_ += prefix.size() + length;
  return true;
}

// A schema or channel id seen again must come with the same record (spec, "Schema", "Channel").
bool LinearReader::keep_schema(const Schema& schema, std::map<std::uint16_t, Schema>& into) {
  if (schema.id == 0) return true;  // "invalid and should be ignored by readers" (spec, "Schema")
  const auto known = schemas_.find(schema.id);
  const Schema* earlier = known != schemas_.end() ? &known->second : nullptr;
  if (earlier == nullptr && into.count(schema.id) != 0) earlier = &into.at(schema.id);
  if (earlier != nullptr && !(*earlier == schema)) {
    stop_at(StopReason::kCorrupt,
            fmt::format("record at byte {}: schema {} defined twice, differently", offset_, schema.id));
    return false;
  }
  if (earlier == nullptr) into.emplace(schema.id, schema);
  return true;
}

bool LinearReader::keep_channel(const Channel& channel, std::map<std::uint16_t, Channel>& into,
                                const std::map<std::uint16_t, Schema>& staged_schemas) {
  if (channel.schema_id != 0 && schemas_.count(channel.schema_id) == 0 &&
      staged_schemas.count(channel.schema_id) == 0) {
    stop_at(StopReason::kCorrupt, fmt::format("record at byte {}: channel {} ({}) before its schema {}",
                                              offset_, channel.id, channel.topic, channel.schema_id));
    return false;
  }
  const auto known = channels_.find(channel.id);
  const Channel* earlier = known != channels_.end() ? &known->second : nullptr;
  if (earlier == nullptr && into.count(channel.id) != 0) earlier = &into.at(channel.id);
  if (earlier != nullptr && !(*earlier == channel)) {
    stop_at(StopReason::kCorrupt,
            fmt::format("record at byte {}: channel {} defined twice, differently", offset_, channel.id));
    return false;
  }
  if (earlier == nullptr) into.emplace(channel.id, channel);
  return true;
}

bool LinearReader::read_chunk(Bytes content) {
  const auto bad = [&](const std::string& why) {
    stop_at(StopReason::kCorrupt, fmt::format("chunk at byte {}: {}", offset_, why));
    return false;
  };
  auto chunk = parse_chunk(content);
  if (!chunk) return bad(chunk.error().message);
  const auto compression = compression_from_name(chunk->compression);
  if (!compression)
    return bad(fmt::format("compression '{}' is not one this reader knows", chunk->compression));
  if (auto out = decompress(*compression, chunk->records, chunk->uncompressed_size, options_.max_chunk_bytes,
                            records_);
      !out)
    return bad(out.error().message);
  if (chunk->uncompressed_crc != 0) {
    const std::uint32_t crc = crc32(records_);
    if (crc != chunk->uncompressed_crc)
      return bad(
          fmt::format("CRC of the records is {:08x}, the chunk says {:08x}", crc, chunk->uncompressed_crc));
  }
  // The whole chunk is checked before anything in it counts: its schemas and channels are
  // staged, its messages queued, and all of it dropped if one record is wrong.
  std::map<std::uint16_t, Schema> schemas;    // new in this chunk
  std::map<std::uint16_t, Channel> channels;  // new in this chunk
  std::vector<Message> messages;
  RecordCursor cursor(records_);
  RecordView record;
  for (;;) {
    auto more = cursor.next(record);
    if (!more) return bad(more.error().message);
    if (!*more) break;
    switch (static_cast<Opcode>(record.opcode)) {
      case Opcode::kSchema: {
        auto schema = parse_schema(record.content);
        if (!schema) return bad(schema.error().message);
        if (!keep_schema(*schema, schemas)) return false;
        break;
      }
      case Opcode::kChannel: {
        auto channel = parse_channel(record.content);
        if (!channel) return bad(channel.error().message);
        if (!keep_channel(*channel, channels, schemas)) return false;
        break;
      }
      case Opcode::kMessage: {
        auto message = parse_message(record.content);
        if (!message) return bad(message.error().message);
        if (channels_.count(message->channel_id) == 0 && channels.count(message->channel_id) == 0)
          return bad(
              fmt::format("a message on channel {}, which nothing before it defines", message->channel_id));
        messages.push_back(*message);
        break;
      }
      default:  // "future spec changes may include others"; private records
        break;
    }
  }
  schemas_.merge(schemas);
  channels_.merge(channels);
  pending_ = std::move(messages);
  next_pending_ = 0;
  ++whole_chunks_;
  return true;
}

}  // namespace hubrt::mcap
