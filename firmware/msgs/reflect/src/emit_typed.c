#include "emit_typed.h"

#include <string.h>

#include "field_desc.h"
#include "names.h"

#define TYPED_NS "::hubrt::msgs::typed::"

typedef enum { CLASS_VIEW, CLASS_REF, CLASS_OWNING } class_kind_t;

/* "pkg" and "Type" of a struct named <pkg>::msg::dds_::<Type>_ (the ROS 2 mapping). */
static bool typed_name(const void* node, char* ns, size_t ns_size, char* type, size_t type_size) {
  char dds[REFLECT_NAME_MAX];
  char ros[REFLECT_NAME_MAX];
  if (!reflect_scoped_name(node, "::", dds, sizeof dds) || !reflect_ros_name(dds, ros, sizeof ros) ||
      ros[0] == '\0') {
    return false;
  }
  const char* first = strchr(ros, '/');
  const char* last = strrchr(ros, '/');
  const int n = snprintf(ns, ns_size, "%.*s", (int)(first - ros), ros);
  const int m = snprintf(type, type_size, "%s", last + 1);
  return n > 0 && (size_t)n < ns_size && m > 0 && (size_t)m < type_size;
}

static bool struct_ok(const idl_struct_t* node, bool allow_sequences);

static bool element_ok(const void* t, bool allow_sequences) {
  const char* kind = NULL;
  const char* c_type = NULL;
  if (idl_is_string(t)) return idl_is_bounded(t);
  if (idl_is_struct(t)) return struct_ok(t, allow_sequences);
  if (idl_is_sequence(t) || idl_is_union(t) || idl_is_enum(t) || idl_is_bitmask(t)) return false;
  return reflect_scalar_spelling(idl_type(t), &kind, &c_type);
}

/* Typed accessors need every string and sequence bounded (storage sized at the bound) and no
 * sequence inside a sequence element (one storage array per sequence field). */
static bool struct_ok(const idl_struct_t* node, bool allow_sequences) {
  char ns[REFLECT_NAME_MAX];
  char type[REFLECT_NAME_MAX];
  if (node->inherit_spec != NULL || !typed_name(node, ns, sizeof ns, type, sizeof type)) return false;
  for (const idl_member_t* m = node->members; m != NULL; m = idl_next(m)) {
    if (m->optional.value || m->external.value) return false;
    for (const idl_declarator_t* d = m->declarators; d != NULL; d = idl_next(d)) {
      if (idl_is_array(d)) return false;
    }
    const void* t = reflect_strip_type(m->type_spec);
    if (idl_is_sequence(t)) {
      if (!allow_sequences || !idl_is_bounded(t)) return false;
      if (!element_ok(reflect_strip_type(((const idl_sequence_t*)t)->type_spec), false)) return false;
    } else if (!element_ok(t, allow_sequences)) {
      return false;
    }
  }
  return true;
}

/* "::pkg::Type" + suffix of a typed struct. */
static bool class_of(const void* node, const char* suffix, char* buf, size_t size) {
  char ns[REFLECT_NAME_MAX];
  char type[REFLECT_NAME_MAX];
  if (!typed_name(node, ns, sizeof ns, type, sizeof type)) return false;
  const int n = snprintf(buf, size, "::%s::%s%s", ns, type, suffix);
  return n > 0 && (size_t)n < size;
}

/* The element traits of a sequence of `t` (typed-ok, see struct_ok). */
static bool traits_of(const void* t, char* buf, size_t size) {
  const char* kind = NULL;
  const char* c_type = NULL;
  int n;
  if (idl_is_string(t)) {
    n = snprintf(buf, size, TYPED_NS "StringElement<%u>", (unsigned)idl_bound(t));
  } else if (idl_is_struct(t)) {
    char view[REFLECT_NAME_MAX];
    char ref[REFLECT_NAME_MAX];
    if (!class_of(t, "View", view, sizeof view) || !class_of(t, "Ref", ref, sizeof ref)) return false;
    n = snprintf(buf, size, TYPED_NS "StructElement<%s, %s>", view, ref);
  } else {
    (void)reflect_scalar_spelling(idl_type(t), &kind, &c_type);
    n = snprintf(buf, size, TYPED_NS "ScalarElement<%s>", c_type);
  }
  return n > 0 && (size_t)n < size;
}

/* The accessors of one field in a class of `kind`; `self` is the C struct expression. */
static bool emit_field(FILE* out, class_kind_t kind, const char* name, const void* t) {
  const char* self = kind == CLASS_OWNING ? "wire_" : "(*wire_)";
  const char* setter_const = kind == CLASS_REF ? " const" : "";
  const char* kind_name = NULL;
  const char* c_type = NULL;
  bool ok = true;
  if (idl_is_sequence(t)) {
    char traits[3 * REFLECT_NAME_MAX];
    const idl_sequence_t* seq = t;
    if (!traits_of(reflect_strip_type(seq->type_spec), traits, sizeof traits)) return false;
    if (kind != CLASS_REF) {
      ok = fprintf(out,
                   "  [[nodiscard]] " TYPED_NS
                   "SequenceView<%s> %s() const noexcept {\n"
                   "    return {%s.%s._buffer, %s.%s._length};\n  }\n",
                   traits, name, self, name, self, name) > 0;
    }
    if (ok && kind != CLASS_VIEW) {
      ok = fprintf(out,
                   "  [[nodiscard]] " TYPED_NS
                   "SequenceRef<%s, %u, decltype(Wire::%s)> %s()%s noexcept {\n"
                   "    return " TYPED_NS "SequenceRef<%s, %u, decltype(Wire::%s)>(%s.%s);\n  }\n",
                   traits, (unsigned)seq->maximum, name, name, setter_const, traits, (unsigned)seq->maximum,
                   name, self, name) > 0;
    }
    return ok;
  }
  if (idl_is_string(t)) {
    ok = fprintf(out,
                 "  [[nodiscard]] std::string_view %s() const noexcept { return " TYPED_NS "view(%s.%s); }\n",
                 name, self, name) > 0;
    if (ok && kind != CLASS_VIEW) {
      ok = fprintf(out,
                   "  // Copies `text`, cut at %u bytes on a UTF-8 boundary; false when cut.\n"
                   "  bool set_%s(std::string_view text)%s noexcept { return " TYPED_NS
                   "assign(%s.%s, text); }\n",
                   (unsigned)idl_bound(t), name, setter_const, self, name) > 0;
    }
    return ok;
  }
  if (idl_is_struct(t)) {
    char view[REFLECT_NAME_MAX];
    char ref[REFLECT_NAME_MAX];
    if (!class_of(t, "View", view, sizeof view) || !class_of(t, "Ref", ref, sizeof ref)) return false;
    if (kind != CLASS_REF) {
      ok = fprintf(out, "  [[nodiscard]] %s %s() const noexcept { return %s(%s.%s); }\n", view, name, view,
                   self, name) > 0;
    }
    if (ok && kind != CLASS_VIEW) {
      ok = fprintf(out, "  [[nodiscard]] %s %s()%s noexcept { return %s(%s.%s); }\n", ref, name, setter_const,
                   ref, self, name) > 0;
    }
    /* A whole-struct copy is a plain copy only when the struct holds no sequence (no pointer). */
    if (ok && kind != CLASS_VIEW && struct_ok(t, false)) {
      ok = fprintf(out, "  void set_%s(const %s& value)%s noexcept { %s.%s = value.wire(); }\n", name, view,
                   setter_const, self, name) > 0;
    }
    return ok;
  }
  (void)reflect_scalar_spelling(idl_type(t), &kind_name, &c_type);
  ok = fprintf(out, "  [[nodiscard]] %s %s() const noexcept { return %s.%s; }\n", c_type, name, self, name) >
       0;
  if (ok && kind != CLASS_VIEW) {
    ok = fprintf(out, "  void set_%s(%s value)%s noexcept { %s.%s = value; }\n", name, c_type, setter_const,
                 self, name) > 0;
  }
  return ok;
}

static bool emit_fields(FILE* out, class_kind_t kind, const idl_struct_t* node) {
  for (const idl_member_t* m = node->members; m != NULL; m = idl_next(m)) {
    for (const idl_declarator_t* d = m->declarators; d != NULL; d = idl_next(d)) {
      if (!emit_field(out, kind, d->name->identifier, reflect_strip_type(m->type_spec))) return false;
    }
  }
  return true;
}

/* Calls `each(out, path, sequence)` for every sequence reachable from `node` through nested
 * structs (not through sequences), `path` the member path ("tool.error_list"). */
typedef bool (*sequence_fn)(FILE* out, const char* path, const idl_sequence_t* seq);

static bool each_sequence(FILE* out, const idl_struct_t* node, const char* prefix, sequence_fn each) {
  for (const idl_member_t* m = node->members; m != NULL; m = idl_next(m)) {
    const void* t = reflect_strip_type(m->type_spec);
    for (const idl_declarator_t* d = m->declarators; d != NULL; d = idl_next(d)) {
      char path[REFLECT_NAME_MAX];
      const int n =
          snprintf(path, sizeof path, "%s%s%s", prefix, prefix[0] != '\0' ? "." : "", d->name->identifier);
      if (n < 0 || (size_t)n >= sizeof path) return false;
      if (idl_is_sequence(t)) {
        if (!each(out, path, t)) return false;
      } else if (idl_is_struct(t)) {
        if (!each_sequence(out, t, path, each)) return false;
      }
    }
  }
  return true;
}

/* "tool.error_list" -> "tool_error_list_storage_" */
static void storage_name(const char* path, char* buf, size_t size) {
  (void)snprintf(buf, size, "%s_storage_", path);
  for (char* c = buf; *c != '\0'; ++c) {
    if (*c == '.') *c = '_';
  }
}

static bool emit_storage(FILE* out, const char* path, const idl_sequence_t* seq) {
  char storage[REFLECT_NAME_MAX + 16];
  storage_name(path, storage, sizeof storage);
  const void* e = reflect_strip_type(seq->type_spec);
  const char* kind = NULL;
  const char* c_type = NULL;
  if (idl_is_string(e)) {
    return fprintf(out, "  char %s[%u][%u]{};\n", storage, (unsigned)seq->maximum,
                   (unsigned)idl_bound(e) + 1u) > 0;
  }
  if (idl_is_struct(e)) {
    char c_name[REFLECT_NAME_MAX];
    if (!reflect_scoped_name(e, "_", c_name, sizeof c_name)) return false;
    return fprintf(out, "  ::%s %s[%u]{};\n", c_name, storage, (unsigned)seq->maximum) > 0;
  }
  (void)reflect_scalar_spelling(idl_type(e), &kind, &c_type);
  return fprintf(out, "  %s %s[%u]{};\n", c_type, storage, (unsigned)seq->maximum) > 0;
}

static bool emit_bind(FILE* out, const char* path, const idl_sequence_t* seq) {
  char storage[REFLECT_NAME_MAX + 16];
  (void)seq;
  storage_name(path, storage, sizeof storage);
  return fprintf(out, "    " TYPED_NS "bind_sequence(wire_.%s, %s);\n", path, storage) > 0;
}

static bool emit_copy(FILE* out, const char* path, const idl_sequence_t* seq) {
  char storage[REFLECT_NAME_MAX + 16];
  (void)seq;
  storage_name(path, storage, sizeof storage);
  return fprintf(out, "    " TYPED_NS "copy_sequence(wire_.%s, %s, from.%s);\n", path, storage, path) > 0;
}

static bool emit_view_or_ref(FILE* out, const idl_struct_t* node, const char* type, const char* c_name,
                             class_kind_t kind) {
  const bool view = kind == CLASS_VIEW;
  const char* suffix = view ? "View" : "Ref";
  bool ok = fprintf(out,
                    "// %s %s: reads%s a %s_ that someone else owns.\n"
                    "class %s%s {\n"
                    " public:\n"
                    "  using Wire = ::%s;\n"
                    "  explicit %s%s(%sWire& wire) noexcept : wire_(&wire) {}\n"
                    "  [[nodiscard]] %sWire& wire() const noexcept { return *wire_; }\n",
                    type, view ? "(read-only view)" : "(read-write view)", view ? "" : " and writes", type,
                    type, suffix, c_name, type, suffix, view ? "const " : "", view ? "const " : "") > 0;
  if (ok && !view) {
    ok =
        fprintf(out,
                "  operator %sView() const noexcept { return %sView(*wire_); }  // NOLINT: a Ref reads too\n",
                type, type) > 0;
  }
  ok = ok && emit_fields(out, view ? CLASS_VIEW : CLASS_REF, node);
  return ok && fprintf(out, "\n private:\n  %sWire* wire_;\n};\n\n", view ? "const " : "") > 0;
}

static bool emit_owning(FILE* out, const idl_struct_t* node, const char* type, const char* c_name) {
  bool ok = fprintf(out,
                    "// %s: owns a %s_ and the storage of each of its sequences, sized at the bound; copies\n"
                    "// copy elements (never share them). Nothing allocates.\n"
                    "class %s {\n"
                    " public:\n"
                    "  using Wire = ::%s;\n"
                    "  %s() noexcept { bind(); }\n"
                    "  // A copy of `from` (sequences cut at their bound).\n"
                    "  explicit %s(const Wire& from) noexcept { copy_from(from); }\n"
                    "  %s(const %s& other) noexcept { copy_from(other.wire_); }\n"
                    "  %s& operator=(const %s& other) noexcept {\n"
                    "    if (this != &other) copy_from(other.wire_);\n"
                    "    return *this;\n"
                    "  }\n"
                    "  ~%s() = default;\n"
                    "  [[nodiscard]] const Wire& wire() const noexcept { return wire_; }\n"
                    "  // The C struct for the transport; its sequences point into this object.\n"
                    "  [[nodiscard]] Wire& wire() noexcept { return wire_; }\n"
                    "  [[nodiscard]] %sView view() const noexcept { return %sView(wire_); }\n"
                    "  [[nodiscard]] %sRef ref() noexcept { return %sRef(wire_); }\n"
                    "  operator %sView() const noexcept { return view(); }  // NOLINT: reads like its view\n",
                    type, type, type, c_name, type, type, type, type, type, type, type, type, type, type,
                    type, type) > 0;
  ok = ok && emit_fields(out, CLASS_OWNING, node);
  ok = ok && fputs("\n private:\n  void bind() noexcept {\n", out) >= 0;
  ok = ok && each_sequence(out, node, "", emit_bind);
  ok = ok && fputs("  }\n  void copy_from(const Wire& from) noexcept {\n    wire_ = from;\n", out) >= 0;
  ok = ok && each_sequence(out, node, "", emit_copy);
  ok = ok && fputs("  }\n\n  Wire wire_{};\n", out) >= 0;
  ok = ok && each_sequence(out, node, "", emit_storage);
  return ok && fputs("};\n\n", out) >= 0;
}

bool reflect_emit_typed_begin(FILE* out, const char* idl_file, const char* stem, const char* const* includes,
                              size_t include_count) {
  bool ok = fprintf(out,
                    "// Generated by hubrt_idlc_reflect from %s. Do not edit.\n"
                    "// Typed accessors (firmware/msgs/README.md) and topic registrations.\n"
                    "#pragma once\n\n"
                    "#include <cstdint>\n"
                    "#include <string_view>\n\n"
                    "#include \"hubrt/dds/topic_type.h\"\n"
                    "#include \"hubrt/msgs/typed.h\"\n"
                    "#include \"%s.h\"\n",
                    idl_file, stem) > 0;
  for (size_t i = 0; ok && i < include_count; i++) {
    char inc_stem[REFLECT_NAME_MAX];
    ok = reflect_file_stem(includes[i], inc_stem, sizeof inc_stem) &&
         fprintf(out, "#include \"%s_typed.h\"\n", inc_stem) > 0;
  }
  return ok && fputs("\n", out) >= 0;
}

bool reflect_emit_typed_struct(FILE* out, const idl_struct_t* node, bool has_descriptor) {
  char c_name[REFLECT_NAME_MAX];
  char ns[REFLECT_NAME_MAX];
  char type[REFLECT_NAME_MAX];
  if (!reflect_scoped_name(node, "_", c_name, sizeof c_name)) return false;
  bool ok = true;
  if (struct_ok(node, true) && typed_name(node, ns, sizeof ns, type, sizeof type)) {
    ok = fprintf(out, "namespace %s {\n\n", ns) > 0 &&
         emit_view_or_ref(out, node, type, c_name, CLASS_VIEW) &&
         emit_view_or_ref(out, node, type, c_name, CLASS_REF) && emit_owning(out, node, type, c_name) &&
         fprintf(out, "}  // namespace %s\n\n", ns) > 0;
  }
  if (ok && has_descriptor)
    ok = fprintf(out, "HUBRT_DDS_TOPIC_TYPE(::%s, ::%s_desc);\n\n", c_name, c_name) > 0;
  return ok;
}

/* The typed struct a State echoes: the type of its member `echo`, when both have typed classes. */
static const idl_struct_t* echoed_command(const idl_struct_t* node) {
  for (const idl_member_t* m = node->members; m != NULL; m = idl_next(m)) {
    for (const idl_declarator_t* d = m->declarators; d != NULL; d = idl_next(d)) {
      const void* t = reflect_strip_type(m->type_spec);
      if (strcmp(idl_identifier(d), "echo") == 0 && idl_is_struct(t) && struct_ok(t, true)) return t;
    }
  }
  return NULL;
}

bool reflect_emit_typed_pair(FILE* pairs, const idl_struct_t* node) {
  const idl_struct_t* command = echoed_command(node);
  char command_view[REFLECT_NAME_MAX];
  char state[REFLECT_NAME_MAX];
  if (command == NULL || !struct_ok(node, true)) return true;
  if (!class_of(command, "View", command_view, sizeof command_view) ||
      !class_of(node, "", state, sizeof state)) {
    return false;
  }
  return fprintf(pairs, "  visit.template operator()<%s, %s>();\n", command_view, state) > 0;
}

bool reflect_emit_typed_end(FILE* out, const char* stem_id, const char* pairs) {
  return fprintf(out,
                 "namespace hubrt::msgs::typed {\n\n"
                 "// Calls visit.template operator()<CommandView, State>() for every State type of this\n"
                 "// file (a struct whose `echo` is a Command type), both with typed classes: for code that\n"
                 "// handles every Command/State pair (the hostile command corpus, tests/hostile).\n"
                 "template <class Visit>\n"
                 "void for_each_command_state_pair_of_%s([[maybe_unused]] Visit&& visit) {\n%s}\n\n"
                 "}  // namespace hubrt::msgs::typed\n",
                 stem_id, pairs) > 0 &&
         fflush(out) == 0;
}
