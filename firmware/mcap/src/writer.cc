#include "hubrt/mcap/writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <utility>

#include <fmt/format.h>

#include "hubrt/base/utf8.h"

namespace hubrt::mcap {
namespace {

Error io_error(const std::string& what, const std::string& path, int err) {
  return make_error(ErrorCode::kIo, fmt::format("{} {}: {}", what, path, std::strerror(err)));
}

bool valid_text(const std::string& s) {
  return is_valid_utf8(s) && s.size() <= UINT32_MAX;
}

}  // namespace

Writer::Writer(int fd, std::string path, WriterOptions options)
    : fd_(fd), path_(std::move(path)), options_(std::move(options)), compressor_(options_.compression) {}

Expected<Writer> Writer::create(const std::string& path, WriterOptions options) {
  if (!valid_text(options.profile) || !valid_text(options.library))
    return make_error(ErrorCode::kInvalidArgument, "MCAP header: profile and library must be UTF-8");
  // O_EXCL: a recording is never overwritten, not even by a second recorder given the same name.
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    if (err == EEXIST)
      return make_error(ErrorCode::kFailedPrecondition, fmt::format("{} exists already", path));
    return io_error("create", path, err);
  }
  Writer writer(fd, path, std::move(options));
  std::vector<std::uint8_t> start(kMagic.begin(), kMagic.end());
  append_record(start, Header{writer.options_.profile, writer.options_.library});
  if (auto written = writer.write_bytes(start, true); !written) return std::move(written).error();
  return writer;
}

Writer::Writer(Writer&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      path_(std::move(other.path_)),
      options_(std::move(other.options_)),
      compressor_(std::move(other.compressor_)),
      file_offset_(other.file_offset_),
      data_crc_(other.data_crc_),
      finished_(std::exchange(other.finished_, true)),
      error_(std::move(other.error_)),
      schemas_(std::move(other.schemas_)),
      schema_written_(std::move(other.schema_written_)),
      channels_(std::move(other.channels_)),
      channel_written_(std::move(other.channel_written_)),
      chunk_(std::move(other.chunk_)),
      compressed_(std::move(other.compressed_)),
      chunk_index_entries_(std::move(other.chunk_index_entries_)),
      chunk_start_time_(other.chunk_start_time_),
      chunk_end_time_(other.chunk_end_time_),
      chunk_has_messages_(other.chunk_has_messages_),
      chunk_indexes_(std::move(other.chunk_indexes_)),
      statistics_(std::move(other.statistics_)) {}

Writer::~Writer() {
  if (!finished_) (void)finish();
  if (fd_ >= 0) ::close(fd_);
}

Expected<void> Writer::failed() const {
  if (finished_) return make_error(ErrorCode::kFailedPrecondition, path_ + ": the file is finished");
  if (error_) return *error_;
  return {};
}

Expected<void> Writer::write_bytes(Bytes bytes, bool in_data_crc) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error_ = io_error("write", path_, n < 0 ? errno : EIO);
      return *error_;
    }
    done += static_cast<std::size_t>(n);
  }
  if (in_data_crc) data_crc_ = crc32(bytes, data_crc_);
  file_offset_ += bytes.size();
  return {};
}

Expected<std::uint16_t> Writer::add_schema(const Schema& schema) {
  if (auto ok = failed(); !ok) return std::move(ok).error();
  if (!valid_text(schema.name) || !valid_text(schema.encoding) || schema.data.size() > UINT32_MAX)
    return make_error(ErrorCode::kInvalidArgument, "MCAP schema: name and encoding must be UTF-8");
  for (const Schema& known : schemas_) {
    if (known.name == schema.name && known.encoding == schema.encoding && known.data == schema.data)
      return known.id;
  }
  if (schemas_.size() >= UINT16_MAX)
    return make_error(ErrorCode::kOutOfRange, "MCAP: more than 65535 schemas");
  Schema added = schema;
  added.id = static_cast<std::uint16_t>(schemas_.size() + 1);
  schemas_.push_back(std::move(added));
  schema_written_.push_back(false);
  return schemas_.back().id;
}

Expected<std::uint16_t> Writer::add_channel(const Channel& channel) {
  if (auto ok = failed(); !ok) return std::move(ok).error();
  if (channel.schema_id > schemas_.size())
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("MCAP channel {}: no schema {}", channel.topic, channel.schema_id));
  bool text_ok = valid_text(channel.topic) && valid_text(channel.message_encoding);
  for (const auto& [key, value] : channel.metadata) text_ok = text_ok && valid_text(key) && valid_text(value);
  if (!text_ok)
    return make_error(ErrorCode::kInvalidArgument, "MCAP channel: topic and metadata must be UTF-8");
  if (channels_.size() > UINT16_MAX)
    return make_error(ErrorCode::kOutOfRange, "MCAP: more than 65536 channels");
  Channel added = channel;
  added.id = static_cast<std::uint16_t>(channels_.size());
  channels_.push_back(std::move(added));
  channel_written_.push_back(false);
  return channels_.back().id;
}

void Writer::write_schema_and_channel(std::uint16_t channel_id) {
  const Channel& channel = channels_[channel_id];
  if (channel.schema_id != 0 && !schema_written_[channel.schema_id - 1U]) {
    append_record(chunk_, schemas_[channel.schema_id - 1U]);
    schema_written_[channel.schema_id - 1U] = true;
    ++statistics_.schema_count;
  }
  append_record(chunk_, channel);
  channel_written_[channel_id] = true;
  ++statistics_.channel_count;
}

Expected<void> Writer::write(const Message& message) {
  if (auto ok = failed(); !ok) return ok;
  if (message.channel_id >= channels_.size())
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("MCAP message: no channel {}", message.channel_id));
  // Close a chunk that this message would take beyond its size, unless it holds nothing yet.
  if (!chunk_.empty() && chunk_.size() + message_record_size(message.data.size()) > options_.chunk_bytes) {
    if (auto closed = close_chunk(); !closed) return closed;
  }
  if (!channel_written_[message.channel_id]) write_schema_and_channel(message.channel_id);
  const std::uint64_t offset = chunk_.size();
  append_record(chunk_, message);
  chunk_index_entries_[message.channel_id].push_back({message.log_time, offset});
  if (!chunk_has_messages_) {
    chunk_start_time_ = chunk_end_time_ = message.log_time;
    chunk_has_messages_ = true;
  }
  chunk_start_time_ = std::min(chunk_start_time_, message.log_time);
  chunk_end_time_ = std::max(chunk_end_time_, message.log_time);
  if (statistics_.message_count == 0)
    statistics_.message_start_time = statistics_.message_end_time = message.log_time;
  statistics_.message_start_time = std::min(statistics_.message_start_time, message.log_time);
  statistics_.message_end_time = std::max(statistics_.message_end_time, message.log_time);
  ++statistics_.message_count;
  ++statistics_.channel_message_counts[message.channel_id];
  if (chunk_.size() >= options_.chunk_bytes) return close_chunk();
  return {};
}

Expected<void> Writer::close_chunk() {
  if (auto ok = failed(); !ok) return ok;
  if (chunk_.empty()) return {};
  if (auto compressed = compressor_.compress(chunk_, compressed_); !compressed) {
    error_ = compressed.error();
    return compressed;
  }
  ChunkView chunk;
  chunk.message_start_time = chunk_has_messages_ ? chunk_start_time_ : 0;
  chunk.message_end_time = chunk_has_messages_ ? chunk_end_time_ : 0;
  chunk.uncompressed_size = chunk_.size();
  chunk.uncompressed_crc = crc32(chunk_);
  chunk.compression = std::string(compression_name(options_.compression));
  chunk.records = compressed_;
  ChunkIndex index;
  index.message_start_time = chunk.message_start_time;
  index.message_end_time = chunk.message_end_time;
  index.chunk_start_offset = file_offset_;
  index.compression = chunk.compression;
  index.compressed_size = compressed_.size();
  index.uncompressed_size = chunk_.size();
  const std::vector<std::uint8_t> head = chunk_record_head(chunk);
  if (auto ok = write_bytes(head, true); !ok) return ok;
  if (auto ok = write_bytes(compressed_, true); !ok) return ok;
  index.chunk_length = head.size() + compressed_.size();
  // "A sequence of Message Index records occurs immediately after each chunk", one per channel
  // with a message in it (spec, "Message Index").
  std::vector<std::uint8_t> indexes;
  for (auto& [channel_id, entries] : chunk_index_entries_) {
    index.message_index_offsets[channel_id] = file_offset_ + indexes.size();
    append_record(indexes, MessageIndex{channel_id, std::move(entries)});
  }
  if (auto ok = write_bytes(indexes, true); !ok) return ok;
  index.message_index_length = indexes.size();
  chunk_indexes_.push_back(std::move(index));
  ++statistics_.chunk_count;
  chunk_.clear();
  chunk_index_entries_.clear();
  chunk_has_messages_ = false;
  return {};
}

Expected<void> Writer::finish() {
  if (auto ok = failed(); !ok) return ok;
  if (auto closed = close_chunk(); !closed) return closed;
  std::vector<std::uint8_t> tail;
  append_record(tail, DataEnd{data_crc_});
  const std::uint64_t summary_start = file_offset_ + tail.size();
  std::vector<std::uint8_t> summary;
  std::vector<SummaryOffset> groups;
  // Records grouped by opcode (spec, "Summary Section"), each group located by a SummaryOffset.
  const auto group = [&](Opcode opcode, auto&& append_group) {
    const std::size_t start = summary.size();
    append_group();
    if (summary.size() > start) groups.push_back({opcode, summary_start + start, summary.size() - start});
  };
  group(Opcode::kSchema, [&] {
    for (std::size_t i = 0; i < schemas_.size(); ++i)
      if (schema_written_[i]) append_record(summary, schemas_[i]);
  });
  group(Opcode::kChannel, [&] {
    for (std::size_t i = 0; i < channels_.size(); ++i)
      if (channel_written_[i]) append_record(summary, channels_[i]);
  });
  group(Opcode::kStatistics, [&] { append_record(summary, statistics_); });
  group(Opcode::kChunkIndex, [&] {
    for (const ChunkIndex& index : chunk_indexes_) append_record(summary, index);
  });
  const std::uint64_t summary_offset_start = summary_start + summary.size();
  for (const SummaryOffset& offset : groups) append_record(summary, offset);
  append_record(summary, Footer{summary_start, summary_offset_start, 0});
  // summary_crc: every byte from the summary's start through summary_offset_start (spec, "Footer").
  const std::uint32_t summary_crc = crc32(Bytes(summary).first(summary.size() - 4));
  for (int i = 0; i < 4; ++i)
    summary[summary.size() - 4 + static_cast<std::size_t>(i)] =
        static_cast<std::uint8_t>(summary_crc >> (8 * i));
  tail.insert(tail.end(), summary.begin(), summary.end());
  tail.insert(tail.end(), kMagic.begin(), kMagic.end());
  if (auto ok = write_bytes(tail, false); !ok) return ok;
  finished_ = true;
  const int synced = ::fdatasync(fd_);
  const int sync_errno = errno;
  ::close(fd_);
  fd_ = -1;
  if (synced != 0) return io_error("sync", path_, sync_errno);
  return {};
}

}  // namespace hubrt::mcap
