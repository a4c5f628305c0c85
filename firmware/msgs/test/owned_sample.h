// A zeroed sample of a generated type that releases what it owns with Cyclone's own
// dds_sample_free(), so tests of our allocation code are checked by an independent free (and by
// ASan in the sanitizer build).
#pragma once

#include <dds/dds.h>

#include "hubrt/msgs/type_info.h"

namespace hubrt::msgs::testing {

template <class T>
class OwnedSample {
 public:
  OwnedSample() = default;
  OwnedSample(const OwnedSample&) = delete;
  OwnedSample& operator=(const OwnedSample&) = delete;
  ~OwnedSample() { dds_sample_free(&value_, type_info_of<T>().descriptor, DDS_FREE_CONTENTS); }

  T& operator*() { return value_; }
  T* operator->() { return &value_; }
  T* get() { return &value_; }
  static const TypeInfo& type() { return type_info_of<T>(); }

 private:
  T value_{};
};

}  // namespace hubrt::msgs::testing
