#include "field_desc.h"

#include <stdio.h>
#include <string.h>

#include "names.h"

/* The C type idlc's C generator uses for each base type. The emitter turns this table into
 * static_asserts, so the compiler confirms it against idlc's header on every build. */
bool reflect_scalar_spelling(idl_type_t type, const char** kind, const char** c_type) {
  switch (type) {
    case IDL_BOOL:
      *kind = "kBool";
      *c_type = "bool";
      return true;
    case IDL_OCTET:
      *kind = "kOctet";
      *c_type = "uint8_t";
      return true;
    case IDL_INT8:
      *kind = "kInt8";
      *c_type = "int8_t";
      return true;
    case IDL_UINT8:
      *kind = "kUInt8";
      *c_type = "uint8_t";
      return true;
    case IDL_SHORT:
    case IDL_INT16:
      *kind = "kInt16";
      *c_type = "int16_t";
      return true;
    case IDL_USHORT:
    case IDL_UINT16:
      *kind = "kUInt16";
      *c_type = "uint16_t";
      return true;
    case IDL_LONG:
    case IDL_INT32:
      *kind = "kInt32";
      *c_type = "int32_t";
      return true;
    case IDL_ULONG:
    case IDL_UINT32:
      *kind = "kUInt32";
      *c_type = "uint32_t";
      return true;
    case IDL_LLONG:
    case IDL_INT64:
      *kind = "kInt64";
      *c_type = "int64_t";
      return true;
    case IDL_ULLONG:
    case IDL_UINT64:
      *kind = "kUInt64";
      *c_type = "uint64_t";
      return true;
    case IDL_FLOAT:
      *kind = "kFloat32";
      *c_type = "float";
      return true;
    case IDL_DOUBLE:
      *kind = "kFloat64";
      *c_type = "double";
      return true;
    default:
      return false;
  }
}

const void* reflect_strip_type(const void* type_spec) {
  return idl_strip(type_spec, IDL_STRIP_ALIASES | IDL_STRIP_FORWARD);
}

/* Fills the element part of `out` from a (non-sequence) type specifier. */
static bool describe_element(const idl_pstate_t* pstate, const char* owner, const void* where,
                             const void* type_spec, reflect_field_desc_t* out) {
  const void* t = reflect_strip_type(type_spec);
  const char* kind = NULL;
  const char* c_type = NULL;
  if (idl_is_declarator(t)) {
    idl_error(pstate, idl_location(where),
              "%s.%s: array typedefs are not supported by the reflection generator", owner, out->name);
    return false;
  }
  if (reflect_scalar_spelling(idl_type(t), &kind, &c_type)) {
    out->element_kind = kind;
    (void)snprintf(out->element_c_type, sizeof out->element_c_type, "%s", c_type);
    return true;
  }
  if (idl_is_string(t)) {
    out->element_kind = "kString";
    if (idl_is_bounded(t)) {
      /* idlc lays string<N> out inline as char[N+1] (also as a sequence element). */
      if (out->is_array) {
        idl_error(pstate, idl_location(where), "%s.%s: arrays of bounded strings are not supported", owner,
                  out->name);
        return false;
      }
      out->string_bound = idl_bound(t);
      (void)snprintf(out->element_c_type, sizeof out->element_c_type, "char[%u]",
                     (unsigned)out->string_bound + 1u);
      return true;
    }
    (void)snprintf(out->element_c_type, sizeof out->element_c_type, "char*");
    return true;
  }
  if (idl_is_struct(t)) {
    out->element_kind = "kStruct";
    if (!reflect_scoped_name(t, "_", out->nested_c_name, sizeof out->nested_c_name)) {
      idl_error(pstate, idl_location(where), "%s.%s: type name too long", owner, out->name);
      return false;
    }
    (void)snprintf(out->element_c_type, sizeof out->element_c_type, "::%s", out->nested_c_name);
    return true;
  }
  idl_error(pstate, idl_location(where), "%s.%s: %s types are not supported by the reflection generator",
            owner, out->name, idl_construct(t));
  return false;
}

bool reflect_describe_field(const idl_pstate_t* pstate, const char* owner, const idl_member_t* member,
                            const idl_declarator_t* declarator, reflect_field_desc_t* out) {
  memset(out, 0, sizeof *out);
  out->name = declarator->name->identifier;
  if (member->optional.value || member->external.value) {
    idl_error(pstate, idl_location(declarator), "%s.%s: @optional and @external members are not supported",
              owner, out->name);
    return false;
  }
  if (idl_is_array(declarator)) {
    const idl_literal_t* dim = declarator->const_expr;
    if (idl_next(dim) != NULL) {
      idl_error(pstate, idl_location(declarator), "%s.%s: multi-dimensional arrays are not supported", owner,
                out->name);
      return false;
    }
    out->is_array = true;
    out->kind = "kArray";
    out->bound = dim->value.uint32;
  }
  const void* t = reflect_strip_type(member->type_spec);
  if (idl_is_sequence(t)) {
    const idl_sequence_t* seq = t;
    if (out->is_array) {
      idl_error(pstate, idl_location(declarator), "%s.%s: arrays of sequences are not supported", owner,
                out->name);
      return false;
    }
    if (idl_is_sequence(reflect_strip_type(seq->type_spec))) {
      idl_error(pstate, idl_location(declarator), "%s.%s: sequences of sequences are not supported", owner,
                out->name);
      return false;
    }
    out->is_sequence = true;
    out->kind = "kSequence";
    out->bound = seq->maximum;
    return describe_element(pstate, owner, declarator, seq->type_spec, out);
  }
  if (!describe_element(pstate, owner, declarator, member->type_spec, out)) return false;
  if (!out->is_array) out->kind = out->element_kind;
  return true;
}
