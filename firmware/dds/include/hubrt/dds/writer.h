// Publishing samples: one writer per topic, writing from caller-owned memory.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>

#include <dds/dds.h>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/dds/entity.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/qos.h"
#include "hubrt/dds/sample_hook.h"
#include "hubrt/dds/topic.h"

namespace hubrt::dds {

namespace detail {
class SerdataPool;
}  // namespace detail

// Called on a Cyclone thread (discovery) when a new reader matched the writer. Same contract as
// DataAvailableCallback: no blocking, no throwing, no deleting the writer; meant to wake a cycle.
using ReaderMatchedCallback = std::function<void()>;

// A writer for a type known by its descriptor only. Move-only; dds_delete() on destruction.
// Thread-safety: write(), matched_readers() and take_new_readers() may be called from any thread
// (Cyclone serialises; a pool block belongs to one write until Cyclone has it; the count is
// atomic); create/move/destroy must not race with them.
class UntypedWriter {
 public:
  // For a keyless topic (all ROS 2 messages) the single instance is registered at once, so that
  // write() does not make Cyclone allocate while no reader is matched.
  // `on_reader_matched` (optional) is installed with the writer, as its publication-matched
  // listener, so that no match is missed between creation and installation; every new match is
  // counted for take_new_readers() whether or not a callback is given.
  // Errors: Cyclone's refusal as "create writer on 'rt/...' in domain N: DDS_RETCODE_...", e.g.
  // for a deleted participant or an inconsistent QoS.
  static Expected<UntypedWriter> create(const Participant& participant, const UntypedTopic& topic,
                                        const Qos& qos = Qos::ros2_default(),
                                        ReaderMatchedCallback on_reader_matched = {});

  // Serialises and sends `sample` (desc->m_size bytes of the topic's type). For a keyless topic
  // (every ROS 2 message) the sample is serialised by Cyclone's own serialiser into a block of this
  // writer's pool and handed over with dds_writecdr (detail::SerdataPool, src/serdata_pool.cc): no
  // heap allocation in steady state, where Cyclone 0.10's dds_write allocates twice per sample
  // over 256 serialised bytes (ddsi_serdata_default.c). The pool grows by a block only while
  // Cyclone holds more samples than ever before (unacknowledged ones of a lagging reliable reader,
  // up to the history depth) and a block only for a sample larger than it has held. Keyed topics
  // and a topic whose sertype could not be found at creation use dds_write. Same bytes on the wire
  // either way (firmware/dds/test/pooled_write_test.cc, tests/dds_write). Errors: kTimeout if a
  // reliable write stayed blocked (never with keep-last); kInvalidArgument for a deleted writer or
  // a sample that does not serialise (e.g. an enum out of range).
  Status write(const void* sample) noexcept;
  // As write(), with `source_time` as the sample's source timestamp instead of this host's clock
  // now: for tools that test how a reader judges a command's age (hubctl send --stamp-offset).
  // Cyclone 0.10.2 has no dds_writecdr_ts: the pooled sample is stamped by hand and written with
  // dds_forwardcdr, which keeps the serdata's timestamp where dds_writecdr overwrites it with
  // dds_time() (src/core/ddsc/src/dds_write.c, dds_writecdr / dds_forwardcdr); without a pool,
  // dds_write_ts. Errors: as write(); kInvalidArgument for a negative time.
  Status write(const void* sample, WallTime source_time) noexcept;

  // Sends `serialized` — a sample as it was on the wire: the 4-byte encapsulation header and the
  // payload, what UntypedReader::take_serialized gives and an MCAP "cdr" message holds — as it is,
  // without decoding it into a struct and encoding it again. Cyclone checks it first as it checks a
  // sample from the network (ddsi_serdata_from_ser_iov: header, and dds_stream_normalize: every
  // length and enum within the type). For tools replaying recordings: allocates a serdata per call.
  // Errors: kInvalidArgument for bytes Cyclone refuses; kFailedPrecondition for a keyed topic or
  // one whose sertype was not found (no write pool); Cyclone's code of the write.
  Status write_serialized(std::span<const std::uint8_t> serialized) noexcept;

  // From now on, write() shows `hook` each sample it serialised into its pool, before Cyclone sends
  // it (the bytes in place: no copy, no second serialisation). A writer without a pool (a keyed
  // topic) shows nothing. nullptr: none. The hook must outlive the writer or be replaced first.
  // Not thread-safe: before the writer is in use.
  void set_sample_hook(SampleHook* hook) noexcept { hook_ = hook; }

  // Number of readers currently matched. Errors: Cyclone's code (deleted writer).
  [[nodiscard]] Result<std::uint32_t> matched_readers() const noexcept;

  // Blocks in the write pool (0 when the writer uses dds_write); for tests and benchmarks.
  [[nodiscard]] std::size_t pooled_blocks() const noexcept;

  // Readers that matched since the last call (0 if none), and resets the count. A reader that
  // matches is reachable from then on: a sample written after this returned a non-zero count
  // reaches it (reliable QoS: the writer keeps it for that reader until acknowledged).
  // Allocation-free, lock-free: for the cycle.
  std::uint64_t take_new_readers() noexcept { return matches_->new_readers.exchange(0); }

  // Whether a reader is matched now, as the publication-matched listener last heard it (Cyclone
  // calls it on every match and unmatch with the current count). Allocation-free, lock-free: for
  // the cycle, to skip building a sample nobody would receive.
  [[nodiscard]] bool has_matched_readers() const noexcept { return matches_->current_readers.load() > 0; }

  // Waits until at least `count` readers are matched, polling with a deadline; for tests and
  // tools, not for the cycle. Errors: kTimeout naming the topic and how many matched.
  Expected<void> wait_for_readers(std::uint32_t count, Duration timeout) const;

  // Blocks until every reliable reader matched now has acknowledged every sample written so far
  // (dds_wait_for_acks), or `timeout` passes; returns at once when no reader is matched. For
  // tools that write and then exit: the writer's end would otherwise cut off retransmissions.
  // Not for the cycle. Errors: kTimeout naming the topic and how many readers are matched;
  // Cyclone's code for a deleted writer.
  Expected<void> wait_for_acks(Duration timeout) const;

  // Writes a sample that carries no data, the unregistration of the keyless topic's one instance,
  // so that wait_for_acks() then shows every reader matched now has heard this writer and will
  // get what it writes next. Why a writer needs that: matching is two-sided, and a reader that
  // the writer matched before the reader matched the writer back drops whatever the writer wrote
  // until then, and acknowledges it. Cyclone 0.10.2 starts a volatile reader from the writer's
  // first heartbeat it hears, treating every sequence number up to that heartbeat's last one as
  // a gap (src/core/ddsi/src/q_receive.c, handle_Heartbeat: gap_end_seq = lastseq + 1 while
  // !pwr->have_seen_heartbeat), and ignores data from a writer before that (handle_regular).
  // Acknowledging this sample, by data or by gap, needs that heartbeat, so once every reader has,
  // the next sample reaches them all. Readers take nothing from it: Cyclone's reader ignores an
  // unregistration from a writer it holds no registration of (dds_rhc_default.c,
  // rhc_unregister_delete_registration: "unknown"), and a reader that had this writer's samples
  // gets an invalid sample (valid_data false), which every hubrt reader and ROS 2 skip.
  // For tools that write a sample once; not for the cycle (allocates). Errors: kFailedPrecondition
  // for a keyed topic, or a writer whose QoS disposes on unregister (Qos::dispose_on_unregister:
  // every reader would see the instance disposed); Cyclone's code of the write.
  Status announce() const;

  [[nodiscard]] dds_entity_t handle() const noexcept { return handle_.get(); }
  [[nodiscard]] const std::string& topic_name() const noexcept { return topic_name_; }

 private:
  static void on_publication_matched(dds_entity_t writer, dds_publication_matched_status_t status,
                                     void* arg) noexcept;
  // Shows the hook (if any) a serialised sample of the pool.
  void show_hook(struct ddsi_serdata* serdata, WallTime source_time) noexcept;

  // What the publication-matched listener updates; heap-held so that it stays in place when the
  // writer moves (Cyclone keeps a pointer to it until the writer is deleted).
  struct MatchWatch {
    std::atomic<std::uint64_t> new_readers{0};
    std::atomic<std::uint32_t> current_readers{0};
    ReaderMatchedCallback callback;
  };

  // Drops the writer's reference to its pool (detail::SerdataPool::release).
  struct PoolRelease {
    void operator()(detail::SerdataPool* pool) const noexcept;
  };

  UntypedWriter(std::unique_ptr<MatchWatch> matches, EntityHandle handle, std::string topic_name,
                const dds_topic_descriptor_t* descriptor) noexcept
      : matches_(std::move(matches)),
        handle_(std::move(handle)),
        topic_name_(std::move(topic_name)),
        descriptor_(descriptor) {}

  // Declared before handle_ so that it is destroyed after the writer it is the listener of.
  std::unique_ptr<MatchWatch> matches_;
  EntityHandle handle_;
  // Declared after handle_ so that it is released while the writer still exists (it drops its
  // instance registration then); serdata Cyclone still holds keep the pool itself alive.
  std::unique_ptr<detail::SerdataPool, PoolRelease> pool_;
  std::string topic_name_;
  const dds_topic_descriptor_t* descriptor_;  // static, generated: outlives every writer
  SampleHook* hook_ = nullptr;
};

// A writer of generated type T. Move-only; thread-safety as UntypedWriter.
template <TopicType T>
class Writer {
 public:
  // Errors: as UntypedWriter::create.
  static Expected<Writer> create(const Participant& participant, const Topic<T>& topic,
                                 const Qos& qos = Qos::ros2_default(),
                                 // A sink, moved on: clang-tidy 14 does not see the move in this template.
                                 // NOLINTNEXTLINE(performance-unnecessary-value-param)
                                 ReaderMatchedCallback on_reader_matched = {}) {
    auto writer = UntypedWriter::create(participant, topic.untyped(), qos, std::move(on_reader_matched));
    if (!writer) return std::move(writer).error();
    return Writer(std::move(*writer));
  }

  // As UntypedWriter::write; `sample` may point its strings into caller-owned fixed buffers.
  Status write(const T& sample) noexcept { return writer_.write(&sample); }
  Status write(const T& sample, WallTime source_time) noexcept { return writer_.write(&sample, source_time); }
  [[nodiscard]] Result<std::uint32_t> matched_readers() const noexcept { return writer_.matched_readers(); }
  std::uint64_t take_new_readers() noexcept { return writer_.take_new_readers(); }
  [[nodiscard]] bool has_matched_readers() const noexcept { return writer_.has_matched_readers(); }
  Expected<void> wait_for_readers(std::uint32_t count, Duration timeout) const {
    return writer_.wait_for_readers(count, timeout);
  }
  [[nodiscard]] std::size_t pooled_blocks() const noexcept { return writer_.pooled_blocks(); }
  [[nodiscard]] const UntypedWriter& untyped() const noexcept { return writer_; }
  [[nodiscard]] dds_entity_t handle() const noexcept { return writer_.handle(); }
  // As UntypedWriter::set_sample_hook.
  void set_sample_hook(SampleHook* hook) noexcept { writer_.set_sample_hook(hook); }

 private:
  explicit Writer(UntypedWriter writer) noexcept : writer_(std::move(writer)) {}
  UntypedWriter writer_;
};

}  // namespace hubrt::dds
