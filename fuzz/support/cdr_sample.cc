#include "cdr_sample.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>

#include <dds/ddsi/ddsi_serdata.h>

#include "hubrt/dds/participant.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/json.h"

namespace hubrt::fuzz {
namespace {

// A participant that talks to nobody: loopback only, no multicast, no peers (SPDP has nowhere to
// go) and no participant index (ports from the OS), so parallel harnesses and tests on the machine
// never see it. Cyclone's configuration reference: docs/manual/options.md, //CycloneDDS/Domain/
// Discovery/Peers and General/AllowMulticast.
constexpr const char* kIsolatedXml =
    "<CycloneDDS><Domain id=\"any\">"
    "<General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
    "<AllowMulticast>false</AllowMulticast></General>"
    "<Discovery><ParticipantIndex>none</ParticipantIndex></Discovery>"
    "</Domain></CycloneDDS>";
constexpr std::uint32_t kDomainId = 231;  // above TestDomain's range (100..230); nothing is sent anyway

[[noreturn]] void die(const std::string& what) {
  std::fprintf(stderr, "fuzz harness setup: %s\n", what.c_str());
  std::abort();
}

const dds::Participant& participant() {
  static const dds::Participant instance = [] {
    auto created = dds::Participant::create(dds::DomainConfig{kDomainId, kIsolatedXml}, "hubrt-fuzz");
    if (!created) die(created.error().message);
    return std::move(*created);
  }();
  return instance;
}

// The sertype of a topic of `type`. Cyclone 0.10 has no public call returning a topic's sertype,
// but every serdata points to its sertype (struct ddsi_serdata::type, dds/ddsi/ddsi_serdata.h):
// write one sample locally and take it back as serdata (dds_takecdr). Local delivery happens in
// the writer's call, so the sample is there when dds_write returns.
const struct ddsi_sertype* sertype_of(const msgs::TypeInfo& type, dds::UntypedTopic& topic) {
  const dds_entity_t reader = dds_create_reader(participant().handle(), topic.handle(), nullptr, nullptr);
  if (reader < 0) die("create reader: " + std::string(dds_strretcode(reader)));
  auto writer = dds::UntypedWriter::create(participant(), topic);
  if (!writer) die(writer.error().message);
  // A zeroed sample has null strings, which the serializer refuses: round-trip it through JSON
  // (null strings read as "") as hubctl send does.
  dds::UntypedSample sample(*type.descriptor);
  if (auto filled = msgs::from_json(type, msgs::to_json(type, sample.data()), sample.data()); !filled) {
    die(filled.error().message);
  }
  if (const Status written = writer->write(sample.data()); !written.is_ok()) die("write the probe sample");
  struct ddsi_serdata* serdata = nullptr;
  dds_sample_info_t info;
  if (dds_takecdr(reader, &serdata, 1, &info, DDS_ANY_STATE) != 1) die("take the probe sample back");
  const struct ddsi_sertype* sertype = serdata->type;
  ddsi_serdata_unref(serdata);
  dds_delete(reader);
  return sertype;  // lives as long as `topic`
}

}  // namespace

CdrDecoder& CdrDecoder::of(const msgs::TypeInfo& type) {
  static std::map<const msgs::TypeInfo*, std::unique_ptr<CdrDecoder>> decoders;
  auto found = decoders.find(&type);
  if (found != decoders.end()) return *found->second;
  if (type.descriptor == nullptr) die(std::string(type.c_name) + " is not a topic type");
  auto topic = dds::UntypedTopic::create_with_dds_name(participant(), *type.descriptor,
                                                       std::string("fuzz_") + std::string(type.c_name));
  if (!topic) die(topic.error().message);
  const struct ddsi_sertype* sertype = sertype_of(type, *topic);
  auto decoder = std::unique_ptr<CdrDecoder>(new CdrDecoder(type, std::move(*topic), sertype));
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
  ddsrt_iovec_t iov;
  iov.iov_base = serialized.data();
  iov.iov_len = static_cast<ddsrt_iov_len_t>(serialized.size());
  // from_ser_iov checks the header and normalises the payload (dds_stream_normalize), returning
  // null for anything malformed: Cyclone 0.10.2 src/core/ddsi/src/ddsi_serdata_default.c,
  // serdata_default_from_ser_iov_common. to_sample then reads it like a reader's take does.
  struct ddsi_serdata* serdata = ddsi_serdata_from_ser_iov(sertype_, SDK_DATA, 1, &iov, serialized.size());
  if (serdata == nullptr) return false;
  const bool read = ddsi_serdata_to_sample(serdata, sample, nullptr, nullptr);
  ddsi_serdata_unref(serdata);
  return read;
}

void CdrDecoder::free_sample(void* sample) const noexcept {
  dds_sample_free(sample, type_->descriptor, DDS_FREE_CONTENTS);
  std::memset(sample, 0, type_->descriptor->m_size);
}

std::vector<std::uint8_t> CdrDecoder::encode(const void* sample) const {
  struct ddsi_serdata* serdata = ddsi_serdata_from_sample(sertype_, SDK_DATA, sample);
  if (serdata == nullptr) die("serialise a seed sample");
  const std::uint32_t size = ddsi_serdata_size(serdata);
  std::vector<std::uint8_t> serialized(size);
  ddsi_serdata_to_ser(serdata, 0, size, serialized.data());
  ddsi_serdata_unref(serdata);
  std::vector<std::uint8_t> input;
  input.push_back(static_cast<std::uint8_t>((serialized[1] == 1 ? 1 : 0) | ((serialized[3] & 3) << 1)));
  input.insert(input.end(), serialized.begin() + 4, serialized.end());
  return input;
}

}  // namespace hubrt::fuzz
