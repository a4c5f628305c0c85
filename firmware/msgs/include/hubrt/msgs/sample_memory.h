// Releasing what a sample owns, for any reflected type — also nested ones, which have no topic
// descriptor for dds_sample_free().
#pragma once

#include "hubrt/msgs/type_info.h"

namespace hubrt::msgs {

// Frees the strings and sequence buffers `sample` owns, following the same rules as
// dds_sample_free(..., DDS_FREE_CONTENTS): strings always, a sequence's buffer only when its
// _release flag is set, elements up to max(_maximum, _length). Then zeroes the sample. Never
// fails. Not thread-safe for the same sample.
void free_contents(const TypeInfo& type, void* sample) noexcept;

}  // namespace hubrt::msgs
