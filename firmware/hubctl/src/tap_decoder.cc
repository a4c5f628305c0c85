#include "tap_decoder.h"

#include <fmt/format.h>

#include "hubrt/dds/domain.h"

namespace hubrt::hubctl {

Expected<dds::Participant> isolated_participant(std::string_view name) {
  // The last domain id: no hubrt test or station uses it, and nothing is sent anyway.
  return dds::Participant::create(dds::DomainConfig{dds::kMaxDomainId, dds::isolated_config_xml()}, name);
}

SampleDecoder& TapDecoder::decoder_of(const std::string& topic) {
  auto found = decoders_.find(topic);
  if (found == decoders_.end()) found = decoders_.emplace(topic, SampleDecoder(tool_, topic)).first;
  return found->second;
}

const void* TapDecoder::deserialize(const TapSample& sample) {
  const TapTopic& topic = *sample.topic;
  if (topic.type == nullptr || topic.type->descriptor == nullptr) return nullptr;
  auto per_type = types_.find(topic.type);
  if (per_type == types_.end()) {
    auto codec = dds::CdrCodec::create(*participant_, *topic.type->descriptor);
    if (!codec) {
      fmt::print(stderr, "{}: {}: {}\n", tool_, topic.ros_name, codec.error().message);
      return nullptr;
    }
    per_type =
        types_.emplace(topic.type, PerType{std::move(*codec), dds::UntypedSample(*topic.type->descriptor)})
            .first;
  }
  PerType& t = per_type->second;
  if (!t.codec.decode(sample.cdr, t.scratch.data())) {
    // Cyclone refuses it (a recording damaged or written by something else: a live sample passed
    // the same check on its way in). Said once per topic, then every 100th time.
    const std::uint64_t refused = ++refused_[topic.ros_name];
    if (refused == 1 || refused % 100 == 0) {
      fmt::print(stderr, "{}: {}: a sample of {} bytes is not a valid {}; skipped ({} so far)\n", tool_,
                 topic.ros_name, sample.cdr.size(), topic.type_name, refused);
    }
    return nullptr;
  }
  return t.scratch.data();
}

std::optional<nlohmann::ordered_json> TapDecoder::decode(const TapSample& sample) {
  const void* data = deserialize(sample);
  if (data == nullptr) return std::nullopt;
  return decoder_of(sample.topic->ros_name).decode(*sample.topic->type, data);
}

}  // namespace hubrt::hubctl
