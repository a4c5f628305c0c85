#include "hubrt/dds/cdr_codec.h"

#include <dds/ddsi/ddsi_serdata.h>
#include <dds/ddsi/ddsi_sertype.h>

#include "sertype_probe.h"

namespace hubrt::dds {

std::string isolated_config_xml() {
  return "<CycloneDDS><Domain id=\"any\">"
         "<General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
         "<AllowMulticast>false</AllowMulticast></General>"
         "<Discovery><ParticipantIndex>none</ParticipantIndex></Discovery>"
         "</Domain></CycloneDDS>";
}

void CdrCodec::SertypeRelease::operator()(const ddsi_sertype* sertype) const noexcept {
  ddsi_sertype_unref(const_cast<ddsi_sertype*>(sertype));
}

Expected<CdrCodec> CdrCodec::create(const Participant& participant,
                                    const dds_topic_descriptor_t& descriptor) {
  std::string name = std::string("hubrt_codec/") + descriptor.m_typename;
  for (char& c : name) c = c == ':' ? '_' : c;  // a scoped IDL name is no topic name
  auto topic = UntypedTopic::create_with_dds_name(participant, descriptor, name);
  if (!topic) return std::move(topic).error();
  const ddsi_sertype* sertype =
      detail::probe_topic_sertype(participant.handle(), topic->handle(), descriptor);
  if (sertype == nullptr) {
    return make_error(ErrorCode::kInternal,
                      std::string("find Cyclone's serialiser of type ") + descriptor.m_typename);
  }
  // The topic holds the sertype too; our own reference keeps it for as long as we decode.
  return CdrCodec(std::move(*topic), ddsi_sertype_ref(sertype));
}

bool CdrCodec::decode(std::span<const std::uint8_t> serialized, void* sample) const noexcept {
  ddsrt_iovec_t iov;
  iov.iov_base = const_cast<std::uint8_t*>(serialized.data());  // read only: from_ser_iov copies
  iov.iov_len = static_cast<ddsrt_iov_len_t>(serialized.size());
  // Null for anything malformed (Cyclone 0.10.2 src/core/ddsi/src/ddsi_serdata_default.c,
  // serdata_default_from_ser_iov_common); to_sample then reads it as a reader's take does.
  ddsi_serdata* serdata = ddsi_serdata_from_ser_iov(sertype_.get(), SDK_DATA, 1, &iov, serialized.size());
  if (serdata == nullptr) return false;
  const bool read = ddsi_serdata_to_sample(serdata, sample, nullptr, nullptr);
  ddsi_serdata_unref(serdata);
  return read;
}

Expected<std::vector<std::uint8_t>> CdrCodec::encode(const void* sample) const {
  ddsi_serdata* serdata = ddsi_serdata_from_sample(sertype_.get(), SDK_DATA, sample);
  if (serdata == nullptr) {
    return make_error(ErrorCode::kInvalidArgument,
                      std::string("a sample of ") + descriptor().m_typename + " that does not serialise");
  }
  const std::uint32_t size = ddsi_serdata_size(serdata);
  std::vector<std::uint8_t> out(size);
  ddsi_serdata_to_ser(serdata, 0, size, out.data());
  ddsi_serdata_unref(serdata);
  return out;
}

}  // namespace hubrt::dds
