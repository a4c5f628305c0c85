// Showing what a tap hands out: a sample's bytes through Cyclone's deserialiser for its type
// (dds::CdrCodec), then as JSON through SampleDecoder (text that is not UTF-8 escaped and reported,
// a sample that cannot be decoded reported and skipped: the stream goes on).
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "hubrt/base/status.h"
#include "hubrt/dds/cdr_codec.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/sample.h"

#include "sample_decoder.h"
#include "tap.h"

namespace hubrt::hubctl {

// A participant that talks to nobody (dds::isolated_config_xml), for decoding a recording without
// joining a domain. Errors: Cyclone's refusal.
Expected<dds::Participant> isolated_participant(std::string_view name);

// One per consumer. Not thread-safe. Must not outlive `participant`.
class TapDecoder {
 public:
  // `tool` prefixes reports ("hubctl echo"); the codecs are made on `participant` (the live tap's,
  // or isolated_participant() for a recording).
  TapDecoder(std::string tool, const dds::Participant& participant)
      : tool_(std::move(tool)), participant_(&participant) {}

  // The sample as JSON; nullopt when it cannot be shown (said on stderr, once per topic and kind).
  std::optional<nlohmann::ordered_json> decode(const TapSample& sample);
  // The sample deserialised into the decoder's scratch sample of its type (valid until the next
  // call); nullptr when Cyclone refuses the bytes (reported).
  const void* deserialize(const TapSample& sample);

 private:
  struct PerType {
    dds::CdrCodec codec;
    dds::UntypedSample scratch;
  };
  SampleDecoder& decoder_of(const std::string& topic);

  std::string tool_;
  const dds::Participant* participant_;
  std::map<const msgs::TypeInfo*, PerType> types_;
  std::map<std::string, SampleDecoder> decoders_;  // by topic
  std::map<std::string, std::uint64_t> refused_;   // samples Cyclone refused, by topic
};

}  // namespace hubrt::hubctl
