#include "recording_player.h"

#include <array>
#include <fstream>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/mcap/records.h"

#include "command_qos.h"
#include "reader_wait.h"
#include "recording_source.h"
#include "session.h"

namespace hubrt::hubctl {
namespace {

struct PlayedTopic {
  std::string ros_name;
  std::optional<dds::UntypedTopic> topic;
  std::optional<dds::UntypedWriter> writer;
  std::uint64_t written = 0;
  std::uint64_t refused = 0;
};

// Commands as hubctl sends them; other topics as their writers offered (the first one's).
dds::Qos qos_for(const TapTopic& topic, std::uint32_t command_lifespan_ms) {
  if (topic.type != nullptr && is_command_type(*topic.type)) return command_writer_qos(command_lifespan_ms);
  if (topic.offered.empty()) return dds::Qos::ros2_default();
  return dds::Qos::from_offered(topic.offered.front());
}

Expected<std::unique_ptr<PlayedTopic>> open_topic(const dds::Participant& participant, const TapTopic& topic,
                                                  std::uint32_t command_lifespan_ms) {
  auto played = std::make_unique<PlayedTopic>();
  played->ros_name = topic.ros_name;
  auto t = dds::UntypedTopic::create(participant, *topic.type->descriptor, topic.ros_name);
  if (!t) return std::move(t).error();
  played->topic.emplace(std::move(*t));
  auto w = dds::UntypedWriter::create(participant, *played->topic,
                                      announceable(qos_for(topic, command_lifespan_ms)));
  if (!w) return std::move(w).error();
  played->writer.emplace(std::move(*w));
  return played;
}

}  // namespace

bool is_mcap_file(const std::string& path) noexcept {
  try {
    std::ifstream in(path, std::ios::binary);
    std::array<char, mcap::kMagic.size()> start{};
    if (!in.read(start.data(), start.size())) return false;
    return std::equal(mcap::kMagic.begin(), mcap::kMagic.end(), start.begin(),
                      [](std::uint8_t m, char c) { return m == static_cast<std::uint8_t>(c); });
  } catch (...) {
    return false;
  }
}

int play_recording(const dds::Participant& participant, const RecordingPlayOptions& options, std::FILE* out) {
  const bool chosen = !options.choice.topics.empty() || !options.choice.regex.empty() || options.choice.all;
  TapFilter filter = [](std::string_view, const msgs::TypeInfo& type) { return is_command_type(type); };
  if (chosen) {
    auto made = make_tap_filter(options.choice);
    if (!made) {
      fmt::print(stderr, "hubctl play: {}\n", made.error().message);
      return kExitUsage;
    }
    filter = std::move(*made);
  }
  auto source = RecordingSource::open(options.files,
                                      RecordingOptions{options.rate, options.start_s, options.end_s, filter});
  if (!source) {
    fmt::print(stderr, "hubctl play: {}\n", source.error().message);
    return kExitUsage;
  }
  std::map<std::uint32_t, std::unique_ptr<PlayedTopic>> topics;
  std::uint64_t written = 0;
  const auto started = std::chrono::steady_clock::now();
  while (!stop_requested()) {
    auto event = (*source)->next(std::chrono::milliseconds(100));
    if (!event) {
      if ((*source)->finished()) break;
      continue;
    }
    const TapTopic& topic = *event->topic;
    if (event->kind == TapEvent::Kind::kTopic) {
      auto opened = open_topic(participant, topic, options.command_lifespan_ms);
      if (!opened) {
        fmt::print(stderr, "hubctl play: {}: {}; not played\n", topic.ros_name, opened.error().message);
        continue;
      }
      // A volatile writer's sample reaches only readers matched before it: wait for the hubs, as
      // `hubctl send --once` does, and keep the recorded spacing after the wait.
      const auto wait_from = std::chrono::steady_clock::now();
      ReaderWait wait;
      wait.settle = true;
      wait.timeout = options.discovery_timeout;
      wait.greet = true;  // matched is not yet heard: a reader that has not would lose the first samples
      auto readers = wait_for_readers(*(*opened)->writer, wait, topic.ros_name);
      (*source)->shift(std::chrono::steady_clock::now() - wait_from);
      if (!readers)
        fmt::print(stderr, "hubctl play: warning: {}; playing it anyway\n", readers.error().message);
      if (!options.quiet)
        fmt::print(out, "playing {} ({}) to {} reader(s)\n", topic.ros_name, topic.type_name,
                   readers ? readers->count : 0);
      topics[topic.id] = std::move(*opened);
      continue;
    }
    if (event->kind != TapEvent::Kind::kSample) continue;
    const auto found = topics.find(topic.id);
    if (found == topics.end()) continue;
    PlayedTopic& played = *found->second;
    const Status status = played.writer->write_serialized(event->sample->cdr);
    if (status.is_ok()) {
      ++played.written;
      ++written;
    } else if (status.code() == ErrorCode::kInvalidArgument) {
      ++played.refused;  // bytes Cyclone would not accept from the network either
    } else {
      fmt::print(stderr, "hubctl play: writing {} failed: {}\n", topic.ros_name, to_string(status.code()));
      return kExitFailed;
    }
  }
  const bool interrupted = stop_requested();
  // The writers go with the process, and with them any retransmission a hub still needs.
  for (const auto& [id, played] : topics) (void)played->writer->wait_for_acks(options.discovery_timeout);
  for (const auto& [id, played] : topics) {
    if (played->refused > 0)
      fmt::print(stderr, "hubctl play: {}: {} recorded message(s) are not valid samples; not sent\n",
                 played->ros_name, played->refused);
  }
  for (const std::string& skipped : (*source)->skipped())
    fmt::print(stderr, "hubctl play: {} skipped: this hubctl does not know its type\n", skipped);
  if (!(*source)->problem().empty()) fmt::print(stderr, "hubctl play: {}\n", (*source)->problem());
  fmt::print(out, "played {} message(s) on {} topic(s) in {:.1f} s{}\n", written, topics.size(),
             to_seconds(std::chrono::steady_clock::now() - started), interrupted ? " (interrupted)" : "");
  if (interrupted) return interrupted_exit_status();
  return written > 0 ? kExitOk : kExitFailed;
}

}  // namespace hubrt::hubctl
