# cmake -DOUT=<file.cc> -DENTRIES=<pkg>|<file.msg>;... -P write_msg_definitions.cmake
# Writes the table of hubrt::msgs::msg_definitions() (hubrt/msgs/definitions.h): each .msg file's
# text as a raw string literal, sorted by ROS name. Run at build time by hubrt_add_msg_definitions().
cmake_minimum_required(VERSION 3.25)
# Sorted by ROS name alone (std::string_view's order, which msg_text()'s binary search relies on).
set(names "")
foreach(entry IN LISTS ENTRIES)
  string(REPLACE "|" ";" parts "${entry}")
  list(GET parts 0 package)
  list(GET parts 1 file)
  get_filename_component(type "${file}" NAME_WE)
  set(name "${package}/msg/${type}")
  if(DEFINED "file_of_${name}")
    message(FATAL_ERROR "two .msg files define ${name}: ${file_of_${name}} and ${file}")
  endif()
  set("file_of_${name}" "${file}")
  list(APPEND names "${name}")
endforeach()
list(SORT names COMPARE STRING CASE SENSITIVE)
set(body "")
foreach(name IN LISTS names)
  file(READ "${file_of_${name}}" text)
  if(text MATCHES "\\)hubrt_msg\"")
    message(FATAL_ERROR "${file_of_${name}} contains the literal's end marker )hubrt_msg\"")
  endif()
  string(APPEND body "    {\"${name}\", R\"hubrt_msg(${text})hubrt_msg\"},\n")
endforeach()
file(WRITE "${OUT}.tmp" "// Generated from the .msg files by firmware/msgs/cmake/write_msg_definitions.cmake. Do not edit.
#include <span>

#include \"hubrt/msgs/definitions.h\"

namespace hubrt::msgs {
namespace {
constexpr MsgDefinition kDefinitions[] = {
${body}};
}  // namespace

std::span<const MsgDefinition> generated_msg_definitions() noexcept { return kDefinitions; }

}  // namespace hubrt::msgs
")
# Only a changed table is written, so that an unchanged one compiles no more.
file(COPY_FILE "${OUT}.tmp" "${OUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUT}.tmp")
