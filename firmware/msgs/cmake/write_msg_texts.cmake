# cmake -DOUT=<file.cc> -DFUNCTION=<name> -DENTRIES=<pkg>|<file.msg>;... -P write_msg_texts.cmake
# Writes hubrt::msgs::reflected::<name>(): the .msg text of each file as a raw string literal, under
# its ROS name (hubrt/msgs/definitions.h). Run at build time by hubrt_add_messages(), so that
# editing a .msg rebuilds the table; the program's registry sorts the tables of its message targets
# (hubrt_messages_write_registry_source).
cmake_minimum_required(VERSION 3.25)
set(body "")
foreach(entry IN LISTS ENTRIES)
  string(REPLACE "|" ";" parts "${entry}")
  list(GET parts 0 package)
  list(GET parts 1 file)
  get_filename_component(type "${file}" NAME_WE)
  file(READ "${file}" text)
  if(text MATCHES "\\)hubrt_msg\"")
    message(FATAL_ERROR "${file} contains the literal's end marker )hubrt_msg\"")
  endif()
  string(APPEND body "    {\"${package}/msg/${type}\", R\"hubrt_msg(${text})hubrt_msg\"},\n")
endforeach()
file(WRITE "${OUT}.tmp" "// Generated from the .msg files by firmware/msgs/cmake/write_msg_texts.cmake. Do not edit.
#include <span>

#include \"hubrt/msgs/definitions.h\"

namespace hubrt::msgs::reflected {
namespace {
constexpr MsgDefinition kTexts[] = {
${body}};
}  // namespace

std::span<const MsgDefinition> ${FUNCTION}() noexcept { return kTexts; }

}  // namespace hubrt::msgs::reflected
")
# Only a changed table is written, so that an unchanged one compiles no more.
file(COPY_FILE "${OUT}.tmp" "${OUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUT}.tmp")
