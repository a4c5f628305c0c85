// Where `hubctl foxglove --allow-publish` writes what clients publish: one DDS writer per command
// topic, with the QoS every hubctl command writer has (command_qos.h), shared by all the client
// channels on that topic and deleted with the last of them. A client's bytes are written as they
// are (UntypedWriter::write_serialized), after Cyclone has checked them as it checks a sample that
// arrives from the network. With DDS Security, the participant's identity decides which writers
// DDS allows at all (an observer's none): no client can do more than that identity.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

#include "hubrt/dds/participant.h"

#include "foxglove_session.h"

namespace hubrt::hubctl::foxglove {

class DdsCommandWriters final : public CommandSink {
 public:
  // `participant` must outlive this and every writer it handed out. At most `max_topics` command
  // topics have a writer at a time.
  DdsCommandWriters(const dds::Participant& participant, std::size_t max_topics);

  // Errors: kInvalidArgument for a name that is no registered command type ("pkg/msg/Type" or
  // "pkg/Type"); kOutOfRange past max_topics; Cyclone's refusal of the topic (another type on it)
  // or of the writer (DDS Security: the identity may not publish there). Thread-safe.
  Expected<std::shared_ptr<CommandWriter>> open(const std::string& topic,
                                                std::string_view schema_name) override;

 private:
  struct Writer;
  const dds::Participant* participant_;
  const std::size_t max_topics_;
  std::mutex mutex_;
  std::map<std::string, std::weak_ptr<Writer>> writers_;  // by topic; expired once no client uses it
};

}  // namespace hubrt::hubctl::foxglove
