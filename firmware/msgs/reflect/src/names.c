#include "names.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "idl/tree.h"

static bool append(char* buf, size_t size, size_t* len, const char* text) {
  const size_t n = strlen(text);
  if (*len + n + 1 > size) return false;
  memcpy(buf + *len, text, n + 1);
  *len += n;
  return true;
}

static bool scoped_name_r(const idl_node_t* node, const char* sep, char* buf, size_t size, size_t* len) {
  if (node == NULL) return true;
  if (!scoped_name_r(node->parent, sep, buf, size, len)) return false;
  if (!idl_is_module(node) && !idl_is_struct(node)) return true;
  if (*len > 0 && !append(buf, size, len, sep)) return false;
  return append(buf, size, len, idl_identifier(node));
}

bool reflect_scoped_name(const void* node, const char* sep, char* buf, size_t size) {
  size_t len = 0;
  if (size == 0) return false;
  buf[0] = '\0';
  return scoped_name_r((const idl_node_t*)node, sep, buf, size, &len);
}

bool reflect_ros_name(const char* dds_name, char* buf, size_t size) {
  static const char* const kinds[] = {"msg", "srv", "action"};
  const char* pkg_end = strstr(dds_name, "::");
  if (size == 0) return false;
  buf[0] = '\0';
  if (pkg_end == NULL) return true;
  for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++) {
    char middle[32];
    (void)snprintf(middle, sizeof middle, "::%s::dds_::", kinds[i]);
    if (strncmp(pkg_end, middle, strlen(middle)) != 0) continue;
    const char* type = pkg_end + strlen(middle);
    const size_t type_len = strlen(type);
    if (type_len < 2 || type[type_len - 1] != '_' || strstr(type, "::") != NULL) return true;
    const int n = snprintf(buf, size, "%.*s/%s/%.*s", (int)(pkg_end - dds_name), dds_name, kinds[i],
                           (int)(type_len - 1), type);
    return n >= 0 && (size_t)n < size;
  }
  return true;
}

bool reflect_c_identifier(const char* text, char* buf, size_t size) {
  size_t len = 0;
  if (isdigit((unsigned char)text[0])) {
    if (size < 2) return false;
    buf[len++] = '_';
  }
  for (const char* p = text; *p != '\0'; p++) {
    if (len + 2 > size) return false;
    buf[len++] = isalnum((unsigned char)*p) ? *p : '_';
  }
  if (len + 1 > size) return false;
  buf[len] = '\0';
  return true;
}

const char* reflect_file_name(const char* path) {
  const char* name = path;
  for (const char* p = path; *p != '\0'; p++) {
    if (*p == '/' || *p == '\\') name = p + 1;
  }
  return name;
}

bool reflect_file_stem(const char* path, char* buf, size_t size) {
  const char* name = reflect_file_name(path);
  const char* dot = strrchr(name, '.');
  const size_t n = dot != NULL ? (size_t)(dot - name) : strlen(name);
  if (n + 1 > size) return false;
  memcpy(buf, name, n);
  buf[n] = '\0';
  return true;
}
