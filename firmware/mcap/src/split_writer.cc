#include "hubrt/mcap/split_writer.h"

#include <algorithm>

#include <fmt/format.h>

namespace hubrt::mcap {
namespace {

constexpr std::uint64_t kMinSplitBytes = 64 * 1024;

}  // namespace

std::string split_file_name(const std::string& path, std::size_t index) {
  const std::size_t slash = path.rfind('/');
  const std::size_t dot = path.rfind('.');
  const std::size_t name_start = slash == std::string::npos ? 0 : slash + 1;
  // "run.mcap" has one, ".hidden" and "a.d/run" have none.
  const bool has_extension = dot != std::string::npos && dot > name_start;
  const std::string stem = has_extension ? path.substr(0, dot) : path;
  const std::string extension = has_extension ? path.substr(dot) : std::string();
  return fmt::format("{}_{}{}", stem, index, extension);
}

SplitWriter::SplitWriter(std::string path, WriterOptions options, SplitOptions split, Writer first)
    : path_(std::move(path)), options_(std::move(options)), split_(split), writer_(std::move(first)) {
  files_.push_back(writer_->path());
}

Expected<SplitWriter> SplitWriter::create(std::string path, WriterOptions options, SplitOptions split) {
  if (split.max_bytes != 0 && split.max_bytes < kMinSplitBytes)
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("a split size of {} bytes; it must be at least {}", split.max_bytes, kMinSplitBytes));
  // Chunks of a quarter of the limit at most, so that a file ends close to it, not a chunk short.
  if (split.max_bytes != 0)
    options.chunk_bytes =  // no more than it was: fits its type on a 32-bit board too
        static_cast<decltype(options.chunk_bytes)>(
            std::min<std::uint64_t>(options.chunk_bytes, split.max_bytes / 4));
  const bool splitting = split.max_bytes != 0 || split.max_duration.count() != 0;
  auto first = Writer::create(splitting ? split_file_name(path, 0) : path, options);
  if (!first) return std::move(first).error();
  return SplitWriter(std::move(path), std::move(options), split, std::move(*first));
}

Expected<std::uint16_t> SplitWriter::add_schema(const Schema& schema) {
  auto id = writer_->add_schema(schema);
  if (id && *id > schemas_.size()) {
    schemas_.push_back(schema);
    schemas_.back().id = *id;
  }
  return id;
}

Expected<std::uint16_t> SplitWriter::add_channel(const Channel& channel) {
  auto id = writer_->add_channel(channel);
  if (id) {
    channels_.push_back(channel);
    channels_.back().id = *id;
  }
  return id;
}

Expected<void> SplitWriter::next_file() {
  if (auto finished = writer_->finish(); !finished) return finished;
  closed_bytes_ += writer_->file_bytes();
  closed_messages_ += writer_->statistics().message_count;
  auto next = Writer::create(split_file_name(path_, files_.size()), options_);
  if (!next) return std::move(next).error();
  writer_.emplace(std::move(*next));
  files_.push_back(writer_->path());
  file_first_log_time_.reset();
  // The same registrations in the same order give the same ids in the new file.
  for (const Schema& schema : schemas_) {
    if (auto id = writer_->add_schema(schema); !id) return std::move(id).error();
  }
  for (const Channel& channel : channels_) {
    if (auto id = writer_->add_channel(channel); !id) return std::move(id).error();
  }
  return {};
}

Expected<void> SplitWriter::write(const Message& message) {
  if (splitting() && writer_->statistics().message_count > 0) {
    const std::uint64_t would_be =
        writer_->file_bytes() + writer_->open_chunk_bytes() + message_record_size(message.data.size());
    const bool too_big = split_.max_bytes != 0 && would_be > split_.max_bytes;
    const auto span = std::chrono::nanoseconds(
        static_cast<std::int64_t>(message.log_time - std::min(message.log_time, *file_first_log_time_)));
    const bool too_long = split_.max_duration.count() != 0 && span >= split_.max_duration;
    if (too_big || too_long) {
      if (auto next = next_file(); !next) return next;
    }
  }
  if (!file_first_log_time_) file_first_log_time_ = message.log_time;
  return writer_->write(message);
}

}  // namespace hubrt::mcap
