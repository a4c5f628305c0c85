// Serialized samples — the 4-byte encapsulation header and the CDR payload, as on the wire and as
// an MCAP "cdr" message holds them — to samples of a type known by its descriptor and back,
// through Cyclone's own (de)serialiser for the type: what hubctl echo and watch use to show what
// the tap took as bytes or a recording holds, and the fuzz harnesses to feed commands to a node.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <dds/dds.h>

#include "hubrt/base/status.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/topic.h"

struct ddsi_sertype;

namespace hubrt::dds {

// The Cyclone configuration of a participant that talks to nobody: loopback only, no multicast,
// no participant index (ports from the OS) and no peers, so SPDP has nowhere to go and parallel
// processes never see it (Cyclone's options: //CycloneDDS/Domain/General/AllowMulticast,
// Discovery/ParticipantIndex). For decoding recordings without joining a domain. Thread-safe.
std::string isolated_config_xml();

// Move-only. Thread-safety: decode() and encode() may be called from any thread at once (Cyclone's
// serdata operations on a sertype are what its receive threads run concurrently); create and
// destroy from one. Must not outlive the participant it was created on.
class CdrCodec {
 public:
  // A codec for `descriptor` on `participant`: a topic of its own (DDS name "hubrt_codec/<type>",
  // ':' as '_'; never announced: Cyclone 0.10 announces endpoints, not topics) whose sertype is
  // found as the write pool finds it (a writer and reader in a partition of their own, deleted
  // at once).
  // Errors: Cyclone's refusal naming the type; kInternal when the sertype was not found.
  static Expected<CdrCodec> create(const Participant& participant, const dds_topic_descriptor_t& descriptor);

  // Deserialises `serialized` into `sample` (descriptor.m_size bytes, zeroed or filled by an earlier
  // decode or take: its buffers are reused as a reader's take does). Cyclone checks the bytes first
  // as it does for a sample from the network (the header, every length and enum:
  // ddsi_serdata_from_ser_iov, dds_stream_normalize); false when it refuses them (sample left as it
  // was). Allocates (the serdata; the sample's strings and sequences when they grow).
  bool decode(std::span<const std::uint8_t> serialized, void* sample) const noexcept;

  // `sample` serialised as a writer would send it (XCDR1, little-endian on this machine), with its
  // header. Errors: kInvalidArgument for a sample that does not serialise (an enum out of range).
  Expected<std::vector<std::uint8_t>> encode(const void* sample) const;

  [[nodiscard]] const dds_topic_descriptor_t& descriptor() const noexcept { return topic_.descriptor(); }

 private:
  struct SertypeRelease {
    void operator()(const ddsi_sertype* sertype) const noexcept;
  };
  CdrCodec(UntypedTopic topic, const ddsi_sertype* sertype) : topic_(std::move(topic)), sertype_(sertype) {}

  UntypedTopic topic_;
  std::unique_ptr<const ddsi_sertype, SertypeRelease> sertype_;  // referenced: lives while we do
};

}  // namespace hubrt::dds
