# Message types from IDL: idlc's C types plus our reflection tables, one static library per call.
#
#   hubrt_add_messages(TARGET <target> FILES <file.idl>... [DEPENDS <message target>...] [NO_REGISTRY])
#
# For each file, idlc writes <stem>.h/.c (C types, topic descriptors) and, through the
# hubrt_idlc_reflect plugin, <stem>_reflect.h/.cpp (TypeInfo tables, hubrt/msgs/type_info.h) and
# <stem>_typed.h (typed accessors and topic registrations, firmware/msgs/README.md).
# <target> is a static library of both; include "<stem>.h" or "<stem>_reflect.h". IDL files may
# #include the IDL of the DEPENDS targets by file name (e.g. #include "hub_msgs_common.idl").
# Unless NO_REGISTRY is given, the types also join hubrt::msgs::all_types() (target
# hubrt_msgs_all). IDL file names must be unique across the project: the generated headers are
# included by bare name.
#
# Cross-compiling: idlc and the plugin are host programs; the generated code is compiled for the
# target. The plugin is built for the host through ExternalProject with HUBRT_HOST_C_COMPILER,
# or taken from HUBRT_IDLC_REFLECT_PLUGIN (a host build's libhubrt_idlc_reflect.so) when set.
include_guard(GLOBAL)

set(HUBRT_IDLC_REFLECT_PLUGIN "" CACHE FILEPATH
    "Prebuilt host hubrt_idlc_reflect plugin (.so) to use instead of building one")
set(HUBRT_HOST_C_COMPILER "cc" CACHE STRING
    "Host C compiler for the idlc plugin when cross-compiling")

# idlc runs on the build machine, also when cross-compiling (the toolchain's find-root must not
# redirect it into the target sysroot).
find_program(HUBRT_IDLC_EXECUTABLE idlc NO_CMAKE_FIND_ROOT_PATH REQUIRED
             DOC "Cyclone DDS IDL compiler (host program, package cyclonedds-tools)")

# Makes the plugin available to hubrt_add_messages(). Call once, from firmware/msgs.
function(hubrt_messages_setup_plugin)
  set(reflect_dir "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../reflect")
  if(HUBRT_IDLC_REFLECT_PLUGIN)
    set(plugin "${HUBRT_IDLC_REFLECT_PLUGIN}")
    set(plugin_depends "${HUBRT_IDLC_REFLECT_PLUGIN}")
  elseif(CMAKE_CROSSCOMPILING)
    include(ExternalProject)
    set(host_bin "${CMAKE_BINARY_DIR}/host-tools/hubrt_idlc_reflect")
    set(plugin "${host_bin}/libhubrt_idlc_reflect.so")
    # A separate configure: no toolchain file, no target flags, the host's Cyclone DDS.
    ExternalProject_Add(hubrt_idlc_reflect_host
      SOURCE_DIR "${reflect_dir}"
      BINARY_DIR "${host_bin}"
      CMAKE_ARGS -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=${HUBRT_HOST_C_COMPILER}
      INSTALL_COMMAND ""
      BUILD_ALWAYS ON
      BUILD_BYPRODUCTS "${plugin}")
    set(plugin_depends hubrt_idlc_reflect_host "${plugin}")
  else()
    add_subdirectory("${reflect_dir}" "${CMAKE_CURRENT_BINARY_DIR}/reflect")
    set(plugin "$<TARGET_FILE:hubrt_idlc_reflect>")
    set(plugin_depends hubrt_idlc_reflect)
  endif()
  # idlc takes -l <lang> as a path when it contains a '/' (else it looks for
  # libcycloneddsidl<lang>.so on the library path): an absolute path needs no LD_LIBRARY_PATH.
  set_property(GLOBAL PROPERTY HUBRT_IDLC_REFLECT_PLUGIN "${plugin}")
  set_property(GLOBAL PROPERTY HUBRT_IDLC_REFLECT_PLUGIN_DEPENDS "${plugin_depends}")
endfunction()

function(hubrt_add_messages)
  cmake_parse_arguments(PARSE_ARGV 0 A "NO_REGISTRY" "TARGET" "FILES;DEPENDS")
  if(A_UNPARSED_ARGUMENTS OR NOT A_TARGET OR NOT A_FILES)
    message(FATAL_ERROR "usage: hubrt_add_messages(TARGET <target> FILES <idl>... [DEPENDS <target>...] "
                        "[NO_REGISTRY]); got: ${ARGV}")
  endif()
  get_property(plugin GLOBAL PROPERTY HUBRT_IDLC_REFLECT_PLUGIN)
  get_property(plugin_depends GLOBAL PROPERTY HUBRT_IDLC_REFLECT_PLUGIN_DEPENDS)
  if(NOT plugin)
    message(FATAL_ERROR "hubrt_add_messages(${A_TARGET}): firmware/msgs must be added before message targets")
  endif()

  set(include_dirs "")
  set(idl_inputs "")
  foreach(dep IN LISTS A_DEPENDS)
    if(TARGET ${dep})
      get_target_property(dep_dirs ${dep} HUBRT_IDL_INCLUDE_DIRS)
      get_target_property(dep_files ${dep} HUBRT_IDL_FILES)
    endif()
    if(NOT TARGET ${dep} OR NOT dep_dirs)
      message(FATAL_ERROR "hubrt_add_messages(${A_TARGET}): DEPENDS '${dep}' is not a message target "
                          "defined (earlier) by hubrt_add_messages()")
    endif()
    list(APPEND include_dirs ${dep_dirs})
    list(APPEND idl_inputs ${dep_files})
  endforeach()

  set(out "${CMAKE_CURRENT_BINARY_DIR}/${A_TARGET}_idl")
  file(MAKE_DIRECTORY "${out}")
  set(files "")
  set(stems "")
  foreach(file IN LISTS A_FILES)
    get_filename_component(abs "${file}" ABSOLUTE)
    if(NOT EXISTS "${abs}")
      message(FATAL_ERROR "hubrt_add_messages(${A_TARGET}): ${abs} does not exist")
    endif()
    get_filename_component(dir "${abs}" DIRECTORY)
    get_filename_component(stem "${abs}" NAME_WE)
    get_property(owner GLOBAL PROPERTY "HUBRT_IDL_STEM_${stem}")
    if(owner AND NOT owner STREQUAL abs)
      message(FATAL_ERROR "hubrt_add_messages(${A_TARGET}): ${abs} and ${owner} are both named ${stem}.idl; "
                          "their generated headers (${stem}.h) would clash. Rename one.")
    endif()
    set_property(GLOBAL PROPERTY "HUBRT_IDL_STEM_${stem}" "${abs}")
    list(APPEND include_dirs "${dir}")
    list(APPEND files "${abs}")
    list(APPEND stems "${stem}")
  endforeach()
  list(REMOVE_DUPLICATES include_dirs)
  list(APPEND idl_inputs ${files})
  list(REMOVE_DUPLICATES idl_inputs)

  # Final (non-appendable) structs, as ROS 2 and XCDR1 peers expect, even where @final is missing.
  set(idlc_args -x final)
  foreach(dir IN LISTS include_dirs)
    list(APPEND idlc_args -I "${dir}")
  endforeach()

  set(sources "")
  foreach(abs stem IN ZIP_LISTS files stems)
    # idlc cannot report what a file includes, so every IDL file this target can see is a
    # dependency: editing any of them regenerates.
    add_custom_command(
      OUTPUT "${out}/${stem}.c" "${out}/${stem}.h"
      COMMAND "${HUBRT_IDLC_EXECUTABLE}" ${idlc_args} -o "${out}" "${abs}"
      DEPENDS ${idl_inputs}
      COMMENT "idlc: C types of ${stem}.idl"
      VERBATIM)
    add_custom_command(
      OUTPUT "${out}/${stem}_reflect.cpp" "${out}/${stem}_reflect.h" "${out}/${stem}_typed.h"
      COMMAND "${HUBRT_IDLC_EXECUTABLE}" -l "${plugin}" ${idlc_args} -o "${out}" "${abs}"
      DEPENDS ${idl_inputs} ${plugin_depends}
      COMMENT "idlc: reflection tables and typed accessors of ${stem}.idl"
      VERBATIM)
    list(APPEND sources "${out}/${stem}.c" "${out}/${stem}.h" "${out}/${stem}_reflect.cpp" "${out}/${stem}_reflect.h"
         "${out}/${stem}_typed.h")
  endforeach()

  # Generated code gets no hubrt warning flags, and its headers are SYSTEM headers for users: its
  # warnings (and clang-tidy's view of idlc's names, e.g. the reserved "dds__") are not ours to fix.
  add_library(${A_TARGET} ${HUBRT_LIBRARY_KIND} ${sources})
  target_include_directories(${A_TARGET} SYSTEM PUBLIC "${out}")
  # hubrt_dds: <stem>_typed.h registers the topic types (hubrt/dds/topic_type.h).
  target_link_libraries(${A_TARGET} PUBLIC CycloneDDS::ddsc hubrt_msgs_reflect hubrt_dds ${A_DEPENDS})
  set_target_properties(${A_TARGET} PROPERTIES
    HUBRT_IDL_INCLUDE_DIRS "${include_dirs}"
    HUBRT_IDL_FILES "${idl_inputs}"
    HUBRT_IDL_STEMS "${stems}")
  if(NOT A_NO_REGISTRY)
    set_property(GLOBAL APPEND PROPERTY HUBRT_MESSAGE_TARGETS ${A_TARGET})
  endif()
endfunction()

# hubrt_messages_add_registry(<target>): a static library defining hubrt::msgs::all_types() over
# every registered message target. Its source is written once all of CMakeLists.txt has run, so
# targets added later (hubs/*) are included without naming them here.
function(hubrt_messages_add_registry target)
  set(file "${CMAKE_CURRENT_BINARY_DIR}/${target}.cc")
  add_library(${target} ${HUBRT_LIBRARY_KIND} "${file}")
  target_link_libraries(${target} PUBLIC hubrt_msgs_reflect)
  if(COMMAND hubrt_target_defaults)
    hubrt_target_defaults(${target})
  endif()
  # Deferred-call arguments are expanded when the call runs, hence EVAL to bind them now.
  cmake_language(EVAL CODE "
    cmake_language(DEFER DIRECTORY [[${CMAKE_SOURCE_DIR}]]
                   CALL _hubrt_messages_write_registry [[${target}]] [[${file}]])")
endfunction()

function(_hubrt_messages_write_registry target file)
  get_property(targets GLOBAL PROPERTY HUBRT_MESSAGE_TARGETS)
  hubrt_messages_write_registry_source("${file}" "every hubrt_add_messages() target" ${targets})
  target_link_libraries(${target} PUBLIC ${targets})
endfunction()

# hubrt_messages_write_registry_source(<file> <what> <message target>...): writes <file>, the
# definition of hubrt::msgs::all_types() over the types of the given message targets (<what> says
# which, in the file's comment). hubrt_msgs_all uses it for every target; a board program's hub
# type registry (hubs/HubTypes.cmake) for the message targets its hub types link.
function(hubrt_messages_write_registry_source file what)
  set(targets ${ARGN})
  set(declarations "")
  set(lists "")
  foreach(t IN LISTS targets)
    get_target_property(t_stems ${t} HUBRT_IDL_STEMS)
    foreach(stem IN LISTS t_stems)
      # Same mangling as the plugin's types_function_name().
      string(MAKE_C_IDENTIFIER "${stem}" id)
      string(APPEND declarations "std::span<const TypeInfo* const> types_of_${id}() noexcept;  // ${t}\n")
      string(APPEND lists "      reflected::types_of_${id}(),\n")
    endforeach()
  endforeach()
  file(CONFIGURE OUTPUT "${file}" @ONLY CONTENT [=[
// Generated by firmware/msgs/cmake/HubrtMessages.cmake: the types of @what@. Do not edit.
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>

#include "hubrt/msgs/all_types.h"

namespace hubrt::msgs {
namespace reflected {
@declarations@
}  // namespace reflected

const TypeRegistry& all_types() noexcept {
  static const TypeRegistry registry = [] {
    TypeRegistry r;
    const std::vector<std::span<const TypeInfo* const>> lists = {
@lists@    };
    for (const auto list : lists) {
      if (auto ok = r.add(list); !ok) {
        // Two tables with one name would already have clashed at link time; a bug if seen.
        std::fprintf(stderr, "hubrt: message registry: %s\n", ok.error().message.c_str());
        std::abort();
      }
    }
    return r;
  }();
  return registry;
}

}  // namespace hubrt::msgs
]=])
endfunction()

# hubrt_add_msg_definitions(TARGET <target> [PACKAGE <pkg> FILES <file.msg>...]...): a library
# defining hubrt::msgs::msg_definitions(), msg_text() and ros2msg_schema() (hubrt/msgs/definitions.h)
# over the .msg files given, each PACKAGE's files following it. The table is written at build time,
# so that editing a .msg rebuilds it. One such library per program.
function(hubrt_add_msg_definitions)
  cmake_parse_arguments(PARSE_ARGV 0 A "" "TARGET" "")
  set(entries "")
  set(files "")
  set(package "")
  set(expect "")
  foreach(arg IN LISTS A_UNPARSED_ARGUMENTS)
    if(arg STREQUAL "PACKAGE")
      set(expect package)
    elseif(arg STREQUAL "FILES")
      set(expect files)
    elseif(expect STREQUAL "package")
      set(package "${arg}")
      set(expect "")
    elseif(expect STREQUAL "files" AND package)
      get_filename_component(abs "${arg}" ABSOLUTE)
      list(APPEND entries "${package}|${abs}")
      list(APPEND files "${abs}")
    else()
      message(FATAL_ERROR "usage: hubrt_add_msg_definitions(TARGET <t> [PACKAGE <pkg> FILES <file.msg>...]...); "
                          "unexpected '${arg}'")
    endif()
  endforeach()
  if(NOT A_TARGET OR NOT entries)
    message(FATAL_ERROR "hubrt_add_msg_definitions: a TARGET and at least one PACKAGE with FILES are needed")
  endif()
  set(out "${CMAKE_CURRENT_BINARY_DIR}/${A_TARGET}_table.cc")
  set(script "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/write_msg_definitions.cmake")
  add_custom_command(OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} "-DOUT=${out}" "-DENTRIES=${entries}" -P "${script}"
    DEPENDS ${files} "${script}"
    COMMENT "Writing the .msg definitions table of ${A_TARGET}"
    VERBATIM)
  hubrt_add_library(${A_TARGET} SOURCES "${out}" "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../src/definitions.cc"
    PUBLIC_DEPS hubrt_base PRIVATE_DEPS hubrt_msgs_drift fmt::fmt)
  target_include_directories(${A_TARGET} PUBLIC "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../include")
endfunction()
