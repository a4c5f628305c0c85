// Receiving samples: taking them one at a time into caller-owned memory whose buffers are reused,
// and a data-available callback to wake whoever waits for them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <dds/dds.h>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/dds/entity.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/qos.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"

namespace hubrt::dds {

// What the reader knows about a taken sample besides its data.
struct SampleInfo {
  WallTime source_time;                          // the writer's wall clock when it wrote
  dds_instance_handle_t publication_handle = 0;  // identifies the writer that sent it
};

// Called on a Cyclone thread when data arrives. It must not block, must not throw, and must not
// delete the reader: it is meant to wake a cycle loop (notify a condition variable, set a flag).
using DataAvailableCallback = std::function<void()>;

// A reader for a type known by its descriptor only. Move-only; dds_delete() on destruction,
// which waits for a running callback to return.
// Thread-safety: take_next() from one thread at a time; matched_writers() from any thread;
// create/move/destroy must not race with use.
class UntypedReader {
 public:
  // `on_data_available` (optional) is installed as the reader's listener at creation.
  // Errors: Cyclone's refusal as "create reader on 'rt/...' in domain N: DDS_RETCODE_...".
  static Expected<UntypedReader> create(const Participant& participant, const UntypedTopic& topic,
                                        const Qos& qos = Qos::ros2_default(),
                                        DataAvailableCallback on_data_available = {});

  // Takes the oldest valid sample into `sample` (desc->m_size bytes of the topic's type),
  // deserialising into its existing strings and sequences and growing them only when too small.
  // Invalid samples (dispose / no-writers notifications) are consumed and skipped; Cyclone frees
  // and zeroes the target's contents when it takes one, so the next take allocates afresh.
  // Returns true if a sample was taken, false if none was waiting. Allocates nothing on our side.
  // Precondition: every pointer inside `sample` is null or was allocated by Cyclone (a zeroed
  // sample, or one filled by an earlier take); free it with dds_sample_free(DDS_FREE_CONTENTS)
  // or use Sample<T> / UntypedSample, which do.
  // Errors: Cyclone's code (e.g. kInvalidArgument for a deleted reader).
  Result<bool> take_next(void* sample, SampleInfo* info = nullptr) noexcept;

  // Takes the oldest valid sample as it was serialized — the 4-byte encapsulation header and the
  // payload (Cyclone 0.10.2: dds_takecdr's serdata, ddsi_serdata_size and ddsi_serdata_to_ser;
  // src/core/ddsi/src/ddsi_serdata_default.c: the CDR header and the payload as received, padding
  // included, byte-swapped by Cyclone's check only when the writer was big-endian) — into `out`
  // (resized to it), without deserialising it. Invalid samples are consumed and skipped.
  // Returns true if a sample was taken. Allocates when `out` must grow: not for the cycle.
  // Errors: Cyclone's code.
  Result<bool> take_serialized(std::vector<std::uint8_t>& out, SampleInfo* info = nullptr);

  // Number of writers currently matched. Errors: Cyclone's code.
  [[nodiscard]] Result<std::uint32_t> matched_writers() const noexcept;

  // Waits until at least `count` writers are matched, polling with a deadline; for tests and
  // tools. Errors: kTimeout naming the topic and how many matched.
  Expected<void> wait_for_writers(std::uint32_t count, Duration timeout) const;

  [[nodiscard]] dds_entity_t handle() const noexcept { return handle_.get(); }
  [[nodiscard]] const std::string& topic_name() const noexcept { return topic_name_; }
  [[nodiscard]] const dds_topic_descriptor_t& descriptor() const noexcept { return *descriptor_; }

 private:
  UntypedReader(std::unique_ptr<DataAvailableCallback> callback, EntityHandle handle, std::string topic_name,
                const dds_topic_descriptor_t& descriptor) noexcept
      : callback_(std::move(callback)),
        handle_(std::move(handle)),
        topic_name_(std::move(topic_name)),
        descriptor_(&descriptor) {}

  // Declared before handle_ so that it is destroyed after it: Cyclone holds a pointer to the
  // callback until the reader is deleted. Heap-held so that moving the reader keeps it in place.
  std::unique_ptr<DataAvailableCallback> callback_;
  EntityHandle handle_;
  std::string topic_name_;
  const dds_topic_descriptor_t* descriptor_;
};

// A reader of generated type T. Move-only; thread-safety as UntypedReader.
template <TopicType T>
class Reader {
 public:
  // Errors: as UntypedReader::create.
  static Expected<Reader> create(const Participant& participant, const Topic<T>& topic,
                                 const Qos& qos = Qos::ros2_default(),
                                 // NOLINTNEXTLINE(performance-unnecessary-value-param): it is moved.
                                 DataAvailableCallback on_data_available = {}) {
    auto reader = UntypedReader::create(participant, topic.untyped(), qos, std::move(on_data_available));
    if (!reader) return std::move(reader).error();
    return Reader(std::move(*reader));
  }

  // As UntypedReader::take_next; `sample` must satisfy the same precondition (T{} does).
  Result<bool> take_next(T& sample, SampleInfo* info = nullptr) noexcept {
    return reader_.take_next(&sample, info);
  }
  Result<bool> take_next(Sample<T>& sample, SampleInfo* info = nullptr) noexcept {
    return reader_.take_next(&sample.get(), info);
  }

  // Takes up to `max_samples` valid samples one by one into `scratch`, calling
  // on_sample(const T&, const SampleInfo&) for each; returns how many were taken. Bounded so that
  // a fast writer cannot keep a cycle busy. Allocates nothing on our side. on_sample must not
  // throw (this function is noexcept).
  // Errors: the first failing take's code (samples handled before it stay handled).
  template <class OnSample>
  Result<std::size_t> take_each(Sample<T>& scratch, std::size_t max_samples, OnSample&& on_sample) noexcept {
    std::size_t taken = 0;
    SampleInfo info;
    while (taken < max_samples) {
      const Result<bool> got = reader_.take_next(&scratch.get(), &info);
      if (!got.is_ok()) return got.status();
      if (!got.value()) break;
      ++taken;
      on_sample(static_cast<const T&>(scratch.get()), static_cast<const SampleInfo&>(info));
    }
    return taken;
  }

  [[nodiscard]] Result<std::uint32_t> matched_writers() const noexcept { return reader_.matched_writers(); }
  Expected<void> wait_for_writers(std::uint32_t count, Duration timeout) const {
    return reader_.wait_for_writers(count, timeout);
  }
  [[nodiscard]] const UntypedReader& untyped() const noexcept { return reader_; }
  [[nodiscard]] dds_entity_t handle() const noexcept { return reader_.handle(); }

 private:
  explicit Reader(UntypedReader reader) noexcept : reader_(std::move(reader)) {}
  UntypedReader reader_;
};

}  // namespace hubrt::dds
