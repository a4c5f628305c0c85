#include "hubrt/mcap/recover.h"

#include <unistd.h>

#include <map>

namespace hubrt::mcap {
namespace {

// Adds the input's schema and channel of `channel_id` to the output once; returns the output's id.
Expected<std::uint16_t> output_channel(const LinearReader& reader, Writer& writer, std::uint16_t channel_id,
                                       std::map<std::uint16_t, std::uint16_t>& channels,
                                       std::map<std::uint16_t, std::uint16_t>& schemas) {
  if (const auto known = channels.find(channel_id); known != channels.end()) return known->second;
  Channel channel = reader.channels().at(channel_id);
  if (channel.schema_id != 0) {
    auto mapped = schemas.find(channel.schema_id);
    if (mapped == schemas.end()) {
      auto id = writer.add_schema(reader.schemas().at(channel.schema_id));
      if (!id) return std::move(id).error();
      mapped = schemas.emplace(channel.schema_id, *id).first;
    }
    channel.schema_id = mapped->second;
  }
  auto id = writer.add_channel(channel);
  if (!id) return std::move(id).error();
  channels.emplace(channel_id, *id);
  return *id;
}

}  // namespace

Expected<Recovered> recover(const std::string& input, const std::string& output, WriterOptions options) {
  auto source = open_file(input);
  if (!source) return std::move(source).error();
  auto reader = LinearReader::open(std::move(*source));
  if (!reader) return std::move(reader).error();
  options.profile = reader->header().profile;
  options.library = reader->header().library;
  auto writer = Writer::create(output, options);
  if (!writer) return std::move(writer).error();
  const auto fail = [&](Error error) -> Expected<Recovered> {
    (void)writer->finish();
    ::unlink(output.c_str());
    return error;
  };
  std::map<std::uint16_t, std::uint16_t> channels;
  std::map<std::uint16_t, std::uint16_t> schemas;
  Recovered recovered;
  while (auto message = reader->next()) {
    auto channel = output_channel(*reader, *writer, message->channel_id, channels, schemas);
    if (!channel) return fail(std::move(channel).error());
    Message copy = *message;
    copy.channel_id = *channel;
    if (auto written = writer->write(copy); !written) return fail(std::move(written).error());
    ++recovered.messages;
  }
  if (auto finished = writer->finish(); !finished) return fail(std::move(finished).error());
  recovered.chunks_read = reader->whole_chunks();
  recovered.bytes_kept = reader->whole_bytes();
  recovered.bytes_dropped = reader->source().size() - reader->whole_bytes();
  recovered.stop = reader->stop();
  return recovered;
}

}  // namespace hubrt::mcap
