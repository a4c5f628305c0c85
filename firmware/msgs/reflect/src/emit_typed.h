/* Writes <stem>_typed.h: the typed C++ accessors of every struct of one IDL file (View, Ref and
 * the owning type, see firmware/msgs/README.md) and the hubrt::dds topic registration of every
 * topic type. Every function returns false when writing failed. */
#ifndef HUBRT_REFLECT_EMIT_TYPED_H
#define HUBRT_REFLECT_EMIT_TYPED_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "idl/processor.h"

bool reflect_emit_typed_begin(FILE* out, const char* idl_file, const char* stem, const char* const* includes,
                              size_t include_count);
/* Accessors for `node` when every string and sequence it holds (through nested structs) is
 * bounded and it is ROS-named; none otherwise (the C struct and the reflection tables remain).
 * `has_descriptor`: idlc emitted a topic descriptor, so the type is registered as a topic type. */
bool reflect_emit_typed_struct(FILE* out, const idl_struct_t* node, bool has_descriptor);
/* One line of the Command/State pair visitor into `pairs` when `node` is a typed State whose `echo`
 * is a typed Command; nothing otherwise. */
bool reflect_emit_typed_pair(FILE* pairs, const idl_struct_t* node);
/* The end of the file: for_each_command_state_pair_of_<stem_id>() over the `pairs` lines. */
bool reflect_emit_typed_end(FILE* out, const char* stem_id, const char* pairs);

#endif
