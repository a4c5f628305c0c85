/* Writes the C++ text of <stem>_reflect.h and <stem>_reflect.cpp (see hubrt/msgs/type_info.h
 * for what the tables mean). Every function returns false when writing failed. */
#ifndef HUBRT_REFLECT_EMIT_H
#define HUBRT_REFLECT_EMIT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "field_desc.h"

typedef struct reflect_struct_desc {
  const char* dds_name; /* "hub_msgs::msg::dds_::DockState_" */
  const char* ros_name; /* "hub_msgs/msg/DockState" or "" */
  const char* c_name;   /* "hub_msgs_msg_dds__DockState_" */
  bool has_descriptor;  /* idlc emitted <c_name>_desc (not @nested) */
  const reflect_field_desc_t* fields;
  size_t field_count;
} reflect_struct_desc_t;

/* `includes`: file names of the IDL files the compiled file #includes, as written. */
bool reflect_emit_header_begin(FILE* out, const char* idl_file, const char* stem, const char* const* includes,
                               size_t include_count);
bool reflect_emit_header_struct(FILE* out, const reflect_struct_desc_t* st);
bool reflect_emit_header_end(FILE* out, const char* idl_file, const char* stem_id);

bool reflect_emit_source_begin(FILE* out, const char* idl_file, const char* stem);
bool reflect_emit_source_struct(FILE* out, const char* idl_file, const reflect_struct_desc_t* st);
/* The list function, types_of_<stem_id>(), over `c_names` in declaration order. */
bool reflect_emit_source_end(FILE* out, const char* stem_id, const char* const* c_names, size_t count);

#endif
