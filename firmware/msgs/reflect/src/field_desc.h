/* One struct member as the reflection tables describe it, read from idlc's AST. */
#ifndef HUBRT_REFLECT_FIELD_DESC_H
#define HUBRT_REFLECT_FIELD_DESC_H

#include <stdbool.h>
#include <stdint.h>

#include "idl/processor.h"

#define REFLECT_NAME_MAX 512

typedef struct reflect_field_desc {
  const char* name;
  const char* kind;         /* FieldKind enumerator, e.g. "kSequence" */
  const char* element_kind; /* FieldKind enumerator of one element (== kind when not a container) */
  uint32_t bound;           /* array length, or sequence maximum (0 = unbounded) */
  uint32_t string_bound;    /* N of string<N> (the field or its element), 0 = unbounded or not a string */
  bool is_sequence;
  bool is_array;
  /* C++ spelling of one element as idlc's C header declares it: "float", "char*", "char[65]", "::T_". */
  char element_c_type[REFLECT_NAME_MAX + 4];
  char nested_c_name[REFLECT_NAME_MAX]; /* C name of the element struct, "" when none */
} reflect_field_desc_t;

/* FieldKind enumerator and C type of an IDL base type ("kUInt32", "uint32_t"); false when it is
 * not one the tables know. */
bool reflect_scalar_spelling(idl_type_t type, const char** kind, const char** c_type);

/* `type_spec` with aliases and forward declarations looked through: the type a field really has. */
const void* reflect_strip_type(const void* type_spec);

/* Describes declarator `declarator` of `member` of the struct named `owner` (for messages).
 * Constructs the tables cannot describe (unions, enums, arrays of bounded strings, @optional, nested
 * sequences, multi-dimensional arrays, ...) are reported with idl_error() at their location;
 * returns false then. */
bool reflect_describe_field(const idl_pstate_t* pstate, const char* owner, const idl_member_t* member,
                            const idl_declarator_t* declarator, reflect_field_desc_t* out);

#endif
