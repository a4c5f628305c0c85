// Owners of samples whose strings and sequences Cyclone allocates (when taking) and must free.
#pragma once

#include <cstring>
#include <utility>

#include <dds/dds.h>

#include "hubrt/dds/topic_type.h"

namespace hubrt::dds {

// One sample of generated type T, zero-initialised, whose contents (strings, sequence buffers)
// are freed with dds_sample_free(..., DDS_FREE_CONTENTS) on destruction. Meant as the target of
// Reader<T>::take_next(), which reuses these buffers from take to take.
// Precondition on destruction: every pointer inside is null or was allocated by Cyclone
// (dds_alloc / dds_string_dup, or filled in by a take). Do not point members at literals or at
// your own buffers here; for writing with borrowed strings use a plain T instead.
// Move-only; a moved-from Sample is zero again. Thread-safety: none (plain data).
template <TopicType T>
class Sample {
 public:
  Sample() noexcept : value_{} {}
  ~Sample() { free_contents(); }
  Sample(const Sample&) = delete;
  Sample& operator=(const Sample&) = delete;
  Sample(Sample&& other) noexcept : value_(std::exchange(other.value_, T{})) {}
  Sample& operator=(Sample&& other) noexcept {
    if (this != &other) {
      free_contents();
      value_ = std::exchange(other.value_, T{});
    }
    return *this;
  }

  T& get() noexcept { return value_; }
  const T& get() const noexcept { return value_; }
  T& operator*() noexcept { return value_; }
  const T& operator*() const noexcept { return value_; }
  T* operator->() noexcept { return &value_; }
  const T* operator->() const noexcept { return &value_; }

 private:
  void free_contents() noexcept {
    dds_sample_free(&value_, &TopicTraits<T>::descriptor(), DDS_FREE_CONTENTS);
    value_ = T{};
  }

  T value_;
};

// A sample of a type known only by its descriptor (hubctl echoes and sends arbitrary types):
// desc->m_size zeroed bytes from dds_alloc, freed with everything inside by
// dds_sample_free(..., DDS_FREE_ALL). Move-only; a moved-from UntypedSample holds nothing
// (data() == nullptr). Thread-safety: none.
class UntypedSample {
 public:
  // Precondition: `descriptor` outlives this object (generated descriptors are static).
  explicit UntypedSample(const dds_topic_descriptor_t& descriptor)
      : descriptor_(&descriptor), data_(dds_alloc(descriptor.m_size)) {
    std::memset(data_, 0, descriptor.m_size);
  }
  ~UntypedSample() { reset(); }
  UntypedSample(const UntypedSample&) = delete;
  UntypedSample& operator=(const UntypedSample&) = delete;
  UntypedSample(UntypedSample&& other) noexcept
      : descriptor_(other.descriptor_), data_(std::exchange(other.data_, nullptr)) {}
  UntypedSample& operator=(UntypedSample&& other) noexcept {
    if (this != &other) {
      reset();
      descriptor_ = other.descriptor_;
      data_ = std::exchange(other.data_, nullptr);
    }
    return *this;
  }

  [[nodiscard]] void* data() noexcept { return data_; }
  [[nodiscard]] const void* data() const noexcept { return data_; }
  [[nodiscard]] const dds_topic_descriptor_t& descriptor() const noexcept { return *descriptor_; }

 private:
  void reset() noexcept {
    if (data_ != nullptr) dds_sample_free(data_, descriptor_, DDS_FREE_ALL);
    data_ = nullptr;
  }

  const dds_topic_descriptor_t* descriptor_;
  void* data_;
};

}  // namespace hubrt::dds
