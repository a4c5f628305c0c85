#include "cdr_sample.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>

#include "hubrt/dds/participant.h"

namespace hubrt::fuzz {
namespace {

constexpr std::uint32_t kDomainId = 231;  // above TestDomain's range (100..230); nothing is sent anyway

[[noreturn]] void die(const std::string& what) {
  std::fprintf(stderr, "fuzz harness setup: %s\n", what.c_str());
  std::abort();
}

const dds::Participant& participant() {
  static const dds::Participant instance = [] {
    auto created =
        dds::Participant::create(dds::DomainConfig{kDomainId, dds::isolated_config_xml()}, "hubrt-fuzz");
    if (!created) die(created.error().message);
    return std::move(*created);
  }();
  return instance;
}

}  // namespace

CdrDecoder& CdrDecoder::of(const msgs::TypeInfo& type) {
  // The participant first: statics are destroyed in reverse order, and a codec must go before the
  // participant it was made on (Cyclone aborted in ddsi_sertype_unref at exit, after every run).
  const dds::Participant& on = participant();
  static std::map<const msgs::TypeInfo*, std::unique_ptr<CdrDecoder>> decoders;
  auto found = decoders.find(&type);
  if (found != decoders.end()) return *found->second;
  if (type.descriptor == nullptr) die(std::string(type.c_name) + " is not a topic type");
  auto codec = dds::CdrCodec::create(on, *type.descriptor);
  if (!codec) die(codec.error().message);
  auto decoder = std::unique_ptr<CdrDecoder>(new CdrDecoder(type, std::move(*codec)));
  return *decoders.emplace(&type, std::move(decoder)).first->second;
}

bool CdrDecoder::decode(std::span<const std::uint8_t> input, void* sample) const {
  if (input.empty()) return false;
  // The encapsulation header (DDS-XTypes 7.6.3.1.2): identifier CDR_BE 00 00 / CDR_LE 00 01,
  // then two option bytes whose low two bits count the padding at the end of the payload.
  std::vector<std::uint8_t> serialized(4 + input.size() - 1);
  serialized[0] = 0;
  serialized[1] = (input[0] & 1) != 0 ? 1 : 0;
  serialized[2] = 0;
  serialized[3] = static_cast<std::uint8_t>((input[0] >> 1) & 3);
  std::memcpy(serialized.data() + 4, input.data() + 1, input.size() - 1);
  return codec_.decode(serialized, sample);
}

void CdrDecoder::free_sample(void* sample) const noexcept {
  dds_sample_free(sample, type_->descriptor, DDS_FREE_CONTENTS);
  std::memset(sample, 0, type_->descriptor->m_size);
}

std::vector<std::uint8_t> CdrDecoder::encode(const void* sample) const {
  auto serialized = codec_.encode(sample);
  if (!serialized) die(serialized.error().message);
  std::vector<std::uint8_t> input;
  input.push_back(static_cast<std::uint8_t>(((*serialized)[1] == 1 ? 1 : 0) | (((*serialized)[3] & 3) << 1)));
  input.insert(input.end(), serialized->begin() + 4, serialized->end());
  return input;
}

}  // namespace hubrt::fuzz
