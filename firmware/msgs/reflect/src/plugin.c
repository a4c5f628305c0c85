/* idlc generator plugin: `idlc -l <dir>/libhubrt_idlc_reflect.so -o OUT file.idl` writes
 * OUT/<stem>_reflect.h and OUT/<stem>_reflect.cpp, the reflection tables of every struct declared
 * in file.idl, and OUT/<stem>_typed.h, their typed C++ accessors and topic registrations (not of the files it
 * includes; each file gets its own tables). idlc looks the entry point `generate` up with dlsym(). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "emit.h"
#include "emit_typed.h"
#include "field_desc.h"
#include "idlc/generator.h"
#include "names.h"

#define REFLECT_PATH_MAX 4096

typedef struct generator {
  const idl_pstate_t* pstate;
  FILE* header;
  FILE* source;
  FILE* typed;
  FILE* pairs; /* the Command/State pair visitor's lines, in memory until the end */
  const char* idl_file;
  const char** c_names; /* structs emitted so far, for the list function */
  size_t c_name_count;
  bool failed;   /* an unsupported construct was reported */
  bool io_error; /* writing failed */
} generator_t;

static bool in_main_file(const generator_t* gen, const void* node) {
  return ((const idl_node_t*)node)->symbol.location.first.source == gen->pstate->sources;
}

static void emit_struct(generator_t* gen, const idl_struct_t* node) {
  char dds_name[REFLECT_NAME_MAX];
  char ros_name[REFLECT_NAME_MAX];
  char c_name[REFLECT_NAME_MAX];
  if (!reflect_scoped_name(node, "::", dds_name, sizeof dds_name) ||
      !reflect_scoped_name(node, "_", c_name, sizeof c_name) ||
      !reflect_ros_name(dds_name, ros_name, sizeof ros_name)) {
    idl_error(gen->pstate, idl_location(node), "struct name too long for the reflection generator");
    gen->failed = true;
    return;
  }
  if (node->inherit_spec != NULL) {
    idl_error(gen->pstate, idl_location(node),
              "%s: struct inheritance is not supported by the reflection generator", dds_name);
    gen->failed = true;
    return;
  }

  size_t count = 0;
  for (const idl_member_t* m = node->members; m != NULL; m = idl_next(m)) {
    for (const idl_declarator_t* d = m->declarators; d != NULL; d = idl_next(d)) count++;
  }
  reflect_field_desc_t* fields = calloc(count == 0 ? 1 : count, sizeof *fields);
  char* kept_name = strdup(c_name);
  const char** names = realloc(gen->c_names, (gen->c_name_count + 1) * sizeof *names);
  if (fields == NULL || kept_name == NULL || names == NULL) {
    free(fields);
    free(kept_name);
    if (names != NULL) gen->c_names = names;
    gen->io_error = true;
    return;
  }
  gen->c_names = names;
  gen->c_names[gen->c_name_count++] = kept_name;

  size_t n = 0;
  bool described = true;
  for (const idl_member_t* m = node->members; m != NULL; m = idl_next(m)) {
    for (const idl_declarator_t* d = m->declarators; d != NULL; d = idl_next(d)) {
      described = reflect_describe_field(gen->pstate, dds_name, m, d, &fields[n++]) && described;
    }
  }
  if (!described) {
    gen->failed = true;
  } else {
    const reflect_struct_desc_t st = {
        .dds_name = dds_name,
        .ros_name = ros_name,
        .c_name = c_name,
        .has_descriptor = idl_is_topic(node, (gen->pstate->config.flags & IDL_FLAG_KEYLIST) != 0),
        .fields = fields,
        .field_count = count,
    };
    if (!reflect_emit_header_struct(gen->header, &st) ||
        !reflect_emit_source_struct(gen->source, gen->idl_file, &st) ||
        !reflect_emit_typed_struct(gen->typed, node, st.has_descriptor) ||
        !reflect_emit_typed_pair(gen->pairs, node)) {
      gen->io_error = true;
    }
  }
  free(fields);
}

static void visit(generator_t* gen, const void* first) {
  for (const void* node = first; node != NULL; node = idl_next(node)) {
    if (idl_is_module(node)) {
      visit(gen, ((const idl_module_t*)node)->definitions);
    } else if (!in_main_file(gen, node)) {
      continue;
    } else if (idl_is_struct(node)) {
      emit_struct(gen, node);
    } else if (idl_is_union(node) || idl_is_enum(node) || idl_is_bitmask(node)) {
      /* Nothing could reflect a member of this type, so say so where it is declared. */
      idl_error(gen->pstate, idl_location(node), "%s '%s' is not supported by the reflection generator",
                idl_construct(node), idl_identifier(node));
      gen->failed = true;
    }
  }
}

static bool collect_includes(const idl_pstate_t* pstate, const char*** out, size_t* count) {
  *count = 0;
  for (const idl_source_t* inc = pstate->sources->includes; inc != NULL; inc = inc->next) (*count)++;
  *out = calloc(*count == 0 ? 1 : *count, sizeof **out);
  if (*out == NULL) return false;
  size_t i = 0;
  for (const idl_source_t* inc = pstate->sources->includes; inc != NULL; inc = inc->next) {
    (*out)[i++] = inc->file->name;
  }
  return true;
}

static int run(generator_t* gen, const char* out_dir) {
  const char* path = gen->pstate->sources->path->name;
  char stem[REFLECT_NAME_MAX];
  char stem_id[REFLECT_NAME_MAX];
  char header_path[REFLECT_PATH_MAX];
  char source_path[REFLECT_PATH_MAX];
  char typed_path[REFLECT_PATH_MAX];
  gen->idl_file = reflect_file_name(path);
  if (!reflect_file_stem(path, stem, sizeof stem) || !reflect_c_identifier(stem, stem_id, sizeof stem_id)) {
    fprintf(stderr, "hubrt_idlc_reflect: file name too long: %s\n", path);
    return IDL_RETCODE_BAD_PARAMETER;
  }
  const int hn = snprintf(header_path, sizeof header_path, "%s/%s_reflect.h", out_dir, stem);
  const int sn = snprintf(source_path, sizeof source_path, "%s/%s_reflect.cpp", out_dir, stem);
  const int tn = snprintf(typed_path, sizeof typed_path, "%s/%s_typed.h", out_dir, stem);
  if (hn < 0 || (size_t)hn >= sizeof header_path || sn < 0 || (size_t)sn >= sizeof source_path || tn < 0 ||
      (size_t)tn >= sizeof typed_path) {
    fprintf(stderr, "hubrt_idlc_reflect: output path too long in %s\n", out_dir);
    return IDL_RETCODE_BAD_PARAMETER;
  }
  gen->header = fopen(header_path, "wb");
  gen->source = fopen(source_path, "wb");
  gen->typed = fopen(typed_path, "wb");
  char* pairs = NULL;
  size_t pairs_size = 0;
  gen->pairs = open_memstream(&pairs, &pairs_size);
  const char** includes = NULL;
  size_t include_count = 0;
  if (gen->header == NULL || gen->source == NULL || gen->typed == NULL || gen->pairs == NULL) {
    fprintf(stderr, "hubrt_idlc_reflect: cannot write %s or %s\n", header_path, source_path);
    gen->io_error = true;
  } else if (!collect_includes(gen->pstate, &includes, &include_count) ||
             !reflect_emit_header_begin(gen->header, gen->idl_file, stem, includes, include_count) ||
             !reflect_emit_source_begin(gen->source, gen->idl_file, stem) ||
             !reflect_emit_typed_begin(gen->typed, gen->idl_file, stem, includes, include_count)) {
    gen->io_error = true;
  } else {
    visit(gen, gen->pstate->root);
    const bool pairs_ok = fclose(gen->pairs) == 0;
    gen->pairs = NULL;
    if (!gen->failed && !gen->io_error &&
        (!pairs_ok || !reflect_emit_header_end(gen->header, gen->idl_file, stem_id) ||
         !reflect_emit_source_end(gen->source, stem_id, gen->c_names, gen->c_name_count) ||
         !reflect_emit_typed_end(gen->typed, stem_id, pairs))) {
      gen->io_error = true;
    }
  }
  if (gen->pairs != NULL) (void)fclose(gen->pairs);
  free(pairs);
  free(includes);
  if (gen->header != NULL && fclose(gen->header) != 0) gen->io_error = true;
  if (gen->source != NULL && fclose(gen->source) != 0) gen->io_error = true;
  if (gen->typed != NULL && fclose(gen->typed) != 0) gen->io_error = true;
  if (gen->failed || gen->io_error) {
    /* Half-written tables must not survive to be compiled by a later build. */
    (void)remove(header_path);
    (void)remove(source_path);
    (void)remove(typed_path);
  }
  if (gen->io_error) {
    fprintf(stderr, "hubrt_idlc_reflect: failed to write %s / %s\n", header_path, source_path);
    return IDL_RETCODE_NO_ACCESS;
  }
  return gen->failed ? IDL_RETCODE_UNSUPPORTED : IDL_RETCODE_OK;
}

__attribute__((visibility("default"))) int generate(const idl_pstate_t* pstate,
                                                    const idlc_generator_config_t* config) {
  generator_t gen = {.pstate = pstate};
  /* idlc passes "" for "-o ." and NULL without -o: both mean the working directory. */
  const char* out_dir = (config != NULL && config->output_dir != NULL && config->output_dir[0] != '\0')
                            ? config->output_dir
                            : ".";
  const int rc = run(&gen, out_dir);
  for (size_t i = 0; i < gen.c_name_count; i++) free((void*)gen.c_names[i]);
  free(gen.c_names);
  return rc;
}
