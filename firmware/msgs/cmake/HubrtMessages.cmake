# Message types from ROS 2 .msg files: the IDL generated from them, idlc's C types and our
# reflection tables, one library per call.
#
#   hubrt_add_messages(TARGET <target>
#                      [IDL <stem> [PACKAGE <pkg>] FILES <file.msg>... [PACKAGE <pkg> FILES ...]]...
#                      [FILES <file.idl>...] [DEPENDS <message target>...] [NO_REGISTRY])
#
# The .msg files are the one source of each type (firmware/msgs/README.md). Each `IDL <stem>`
# group becomes <stem>.idl, written at build time by hubrt_msg2idl (msg2idl/, the mapping in
# hubrt/msgs/msg_to_idl.h); PACKAGE (default hub_msgs) names the ROS 2 package of the FILES after
# it. For each IDL file idlc writes <stem>.h/.c (C types, topic descriptors) and, through the
# hubrt_idlc_reflect plugin, <stem>_reflect.h/.cpp (TypeInfo tables, hubrt/msgs/type_info.h) and
# <stem>_typed.h (typed accessors and topic registrations). <target> is a library of them all plus
# the .msg texts (hubrt/msgs/definitions.h); include "<stem>.h", "<stem>_reflect.h" or
# "<stem>_typed.h". A .msg may use the types of its own target and of the DEPENDS targets
# (hub_msgs/StateHeader from hubrt_msgs_common). FILES of hand-written .idl, before any IDL group,
# are for test fixtures of the plugin (shapes a .msg cannot write). Unless NO_REGISTRY is given,
# the types join hubrt::msgs::all_types() (target hubrt_msgs_all). IDL stems must be unique across
# the project: the generated headers are included by bare name.
#
# Cross-compiling: hubrt_msg2idl, idlc and the plugin are host programs; the generated code is
# compiled for the target. The generator and the plugin are built for the host through
# ExternalProject (HUBRT_HOST_CXX_COMPILER, HUBRT_HOST_C_COMPILER), or taken prebuilt from
# HUBRT_MSG2IDL and HUBRT_IDLC_REFLECT_PLUGIN when set.
include_guard(GLOBAL)

set(HUBRT_IDLC_REFLECT_PLUGIN "" CACHE FILEPATH
    "Prebuilt host hubrt_idlc_reflect plugin (.so) to use instead of building one")
set(HUBRT_HOST_C_COMPILER "cc" CACHE STRING
    "Host C compiler for the idlc plugin when cross-compiling")
set(HUBRT_MSG2IDL "" CACHE FILEPATH "Prebuilt host hubrt_msg2idl to use instead of building one")
set(HUBRT_HOST_CXX_COMPILER "c++" CACHE STRING
    "Host C++ compiler for hubrt_msg2idl when cross-compiling")

# idlc runs on the build machine, also when cross-compiling (the toolchain's find-root must not
# redirect it into the target sysroot).
find_program(HUBRT_IDLC_EXECUTABLE idlc NO_CMAKE_FIND_ROOT_PATH REQUIRED
             DOC "Cyclone DDS IDL compiler (host program, package cyclonedds-tools)")

# A host tool of the build (<dir> is its own CMake project): `prebuilt` when given; else, when
# cross-compiling, built for the host through ExternalProject with the host compiler
# (-D<compiler_var>=<compiler>: a separate configure, no toolchain file, no target flags, the host's
# libraries); else the project's own target <target> from add_subdirectory(<dir>). Sets <out> to
# its file and <out>_DEPENDS to what uses of it depend on. A `prebuilt` that does not exist is
# not used.
function(_hubrt_host_tool out target dir file prebuilt compiler_var compiler)
  if(prebuilt AND NOT EXISTS "${prebuilt}")
    # A tree configured with another build's tool (toolchain/default-suite) after that build went.
    message(STATUS "${target}: the prebuilt ${prebuilt} is not there; building one")
    set(prebuilt "")
  endif()
  if(prebuilt)
    set(path "${prebuilt}")
    set(depends "${prebuilt}")
  elseif(CMAKE_CROSSCOMPILING)
    include(ExternalProject)
    set(host_bin "${CMAKE_BINARY_DIR}/host-tools/${target}")
    set(path "${host_bin}/${file}")
    ExternalProject_Add(${target}_host
      SOURCE_DIR "${dir}"
      BINARY_DIR "${host_bin}"
      CMAKE_ARGS -DCMAKE_BUILD_TYPE=Release -D${compiler_var}=${compiler}
      INSTALL_COMMAND ""
      BUILD_ALWAYS ON
      BUILD_BYPRODUCTS "${path}")
    set(depends ${target}_host "${path}")
  else()
    get_filename_component(name "${dir}" NAME)
    add_subdirectory("${dir}" "${CMAKE_CURRENT_BINARY_DIR}/${name}")
    set(path "$<TARGET_FILE:${target}>")
    set(depends ${target})
  endif()
  set(${out} "${path}" PARENT_SCOPE)
  set(${out}_DEPENDS "${depends}" PARENT_SCOPE)
endfunction()

# Makes the plugin and the generator available to hubrt_add_messages(). Call once, from firmware/msgs.
function(hubrt_messages_setup_plugin)
  _hubrt_host_tool(plugin hubrt_idlc_reflect "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../reflect"
                   libhubrt_idlc_reflect.so "${HUBRT_IDLC_REFLECT_PLUGIN}" CMAKE_C_COMPILER "${HUBRT_HOST_C_COMPILER}")
  _hubrt_host_tool(msg2idl hubrt_msg2idl "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../msg2idl"
                   hubrt_msg2idl "${HUBRT_MSG2IDL}" CMAKE_CXX_COMPILER "${HUBRT_HOST_CXX_COMPILER}")
  set_property(GLOBAL PROPERTY HUBRT_MSG2IDL "${msg2idl}")
  set_property(GLOBAL PROPERTY HUBRT_MSG2IDL_DEPENDS "${msg2idl_DEPENDS}")
  set(plugin_depends "${plugin_DEPENDS}")
  # idlc takes -l <lang> as a path when it contains a '/' (else it looks for
  # libcycloneddsidl<lang>.so on the library path): an absolute path needs no LD_LIBRARY_PATH.
  set_property(GLOBAL PROPERTY HUBRT_IDLC_REFLECT_PLUGIN "${plugin}")
  set_property(GLOBAL PROPERTY HUBRT_IDLC_REFLECT_PLUGIN_DEPENDS "${plugin_depends}")
endfunction()

function(hubrt_add_messages)
  _hubrt_messages_parse_arguments(A ${ARGN})
  get_property(plugin GLOBAL PROPERTY HUBRT_IDLC_REFLECT_PLUGIN)
  get_property(plugin_depends GLOBAL PROPERTY HUBRT_IDLC_REFLECT_PLUGIN_DEPENDS)
  get_property(msg2idl GLOBAL PROPERTY HUBRT_MSG2IDL)
  get_property(msg2idl_depends GLOBAL PROPERTY HUBRT_MSG2IDL_DEPENDS)
  if(NOT plugin)
    message(FATAL_ERROR "hubrt_add_messages(${A_TARGET}): firmware/msgs must be added before message targets")
  endif()

  set(include_dirs "")
  set(idl_inputs "")
  set(known "")
  foreach(dep IN LISTS A_DEPENDS)
    if(TARGET ${dep})
      get_target_property(dep_dirs ${dep} HUBRT_IDL_INCLUDE_DIRS)
      get_target_property(dep_files ${dep} HUBRT_IDL_FILES)
      get_target_property(dep_known ${dep} HUBRT_MSG_KNOWN)
    endif()
    if(NOT TARGET ${dep} OR NOT dep_dirs)
      message(FATAL_ERROR "hubrt_add_messages(${A_TARGET}): DEPENDS '${dep}' is not a message target "
                          "defined (earlier) by hubrt_add_messages()")
    endif()
    list(APPEND include_dirs ${dep_dirs})
    list(APPEND idl_inputs ${dep_files})
    if(dep_known)
      list(APPEND known ${dep_known})
    endif()
  endforeach()

  set(out "${CMAKE_CURRENT_BINARY_DIR}/${A_TARGET}_idl")
  file(MAKE_DIRECTORY "${out}")
  set(files "")
  set(stems "")
  set(msg_entries "")  # pkg|abs.msg, for the .msg texts
  set(msg_files "")
  # Each IDL group: the types it defines (pkg/Type=stem), known to every later group and to the
  # targets that DEPEND on this one.
  foreach(group IN LISTS A_GROUPS)
    foreach(entry IN LISTS A_GROUP_${group})
      string(REPLACE "|" ";" parts "${entry}")
      list(GET parts 0 package)
      list(GET parts 1 abs)
      get_filename_component(type "${abs}" NAME_WE)
      get_property(owner GLOBAL PROPERTY "HUBRT_MSG_TYPE_${package}/${type}")
      if(owner AND NOT owner STREQUAL abs)
        message(FATAL_ERROR "hubrt_add_messages(${A_TARGET}): ${abs} and ${owner} both define ${package}/${type}")
      endif()
      set_property(GLOBAL PROPERTY "HUBRT_MSG_TYPE_${package}/${type}" "${abs}")
      list(APPEND known "${package}/${type}=${group}")
      list(APPEND msg_entries "${package}|${abs}")
      list(APPEND msg_files "${abs}")
    endforeach()
  endforeach()
  foreach(group IN LISTS A_GROUPS)
    set(idl "${out}/${group}.idl")
    set(msg_args "")
    set(group_files "")
    foreach(entry IN LISTS A_GROUP_${group})
      string(REPLACE "|" ";" parts "${entry}")
      list(GET parts 0 package)
      list(GET parts 1 abs)
      list(APPEND msg_args --msg "${package}=${abs}")
      list(APPEND group_files "${abs}")
    endforeach()
    set(known_args "")
    foreach(k IN LISTS known)
      list(APPEND known_args --known "${k}")
    endforeach()
    add_custom_command(
      OUTPUT "${idl}"
      COMMAND "${msg2idl}" --stem "${group}" --out "${idl}" ${msg_args} ${known_args}
      DEPENDS ${group_files} ${msg2idl_depends}
      COMMENT "hubrt_msg2idl: ${group}.idl from its .msg files"
      VERBATIM)
    list(APPEND A_IDL_FILES "${idl}")
  endforeach()
  if(A_GROUPS)
    list(APPEND include_dirs "${out}")
  endif()

  foreach(abs IN LISTS A_IDL_FILES)
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

  # The .msg texts of the target's types (hubrt/msgs/definitions.h), written at build time so that
  # editing a .msg rebuilds them; the program's registry lists them (hubrt_messages_write_registry_source).
  string(MAKE_C_IDENTIFIER "${A_TARGET}" target_id)
  if(msg_entries)
    set(texts "${out}/${A_TARGET}_msg_texts.cc")
    set(script "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/write_msg_texts.cmake")
    add_custom_command(OUTPUT "${texts}"
      COMMAND ${CMAKE_COMMAND} "-DOUT=${texts}" "-DFUNCTION=msg_texts_of_${target_id}" "-DENTRIES=${msg_entries}"
              -P "${script}"
      DEPENDS ${msg_files} "${script}"
      COMMENT "The .msg texts of ${A_TARGET}"
      VERBATIM)
    list(APPEND sources "${texts}")
  endif()

  # Generated code gets no hubrt warning flags, and its headers are SYSTEM headers for users: its
  # warnings (and clang-tidy's view of idlc's names, e.g. the reserved "dds__") are not ours to fix.
  add_library(${A_TARGET} ${HUBRT_LIBRARY_KIND} ${sources})
  target_include_directories(${A_TARGET} SYSTEM PUBLIC "${out}")
  # hubrt_dds: <stem>_typed.h registers the topic types (hubrt/dds/topic_type.h).
  target_link_libraries(${A_TARGET} PUBLIC CycloneDDS::ddsc hubrt_msgs_reflect hubrt_dds ${A_DEPENDS})
  list(REMOVE_DUPLICATES known)
  set_target_properties(${A_TARGET} PROPERTIES
    HUBRT_IDL_INCLUDE_DIRS "${include_dirs}"
    HUBRT_IDL_FILES "${idl_inputs}"
    HUBRT_IDL_STEMS "${stems}"
    HUBRT_MSG_KNOWN "${known}"
    HUBRT_MSG_FILES "${msg_files}"
    HUBRT_MSG_ENTRIES "${msg_entries}"
    # Exported with the target (toolchain/cmake/HubrtExport.cmake), for message targets built
    # against this build elsewhere (DEPENDS hubrt_msgs_common there) and their registries.
    EXPORT_PROPERTIES "HUBRT_IDL_INCLUDE_DIRS;HUBRT_IDL_FILES;HUBRT_IDL_STEMS;HUBRT_MSG_KNOWN;HUBRT_MSG_FILES;HUBRT_MSG_ENTRIES;HUBRT_MSG_TEXTS_FUNCTION")
  if(msg_entries)
    set_target_properties(${A_TARGET} PROPERTIES HUBRT_MSG_TEXTS_FUNCTION "msg_texts_of_${target_id}")
  else()
    set_target_properties(${A_TARGET} PROPERTIES HUBRT_MSG_TEXTS_FUNCTION "")
  endif()
  if(NOT A_NO_REGISTRY)
    set_property(GLOBAL APPEND PROPERTY HUBRT_MESSAGE_TARGETS ${A_TARGET})
  endif()
endfunction()

# Reads hubrt_add_messages()'s arguments into <prefix>_TARGET, _DEPENDS, _NO_REGISTRY, _IDL_FILES
# (hand-written .idl), _GROUPS (the IDL stems of .msg groups) and _GROUP_<stem> (pkg|abs.msg each).
macro(_hubrt_messages_parse_arguments prefix)
  set(${prefix}_TARGET "")
  set(${prefix}_DEPENDS "")
  set(${prefix}_NO_REGISTRY FALSE)
  set(${prefix}_IDL_FILES "")
  set(${prefix}_GROUPS "")
  set(_hubrt_expect "")
  set(_hubrt_group "")
  set(_hubrt_package hub_msgs)
  foreach(_hubrt_arg IN ITEMS ${ARGN})
    if(_hubrt_arg MATCHES "^(TARGET|IDL|PACKAGE|FILES|DEPENDS)$")
      set(_hubrt_expect "${_hubrt_arg}")
    elseif(_hubrt_arg STREQUAL "NO_REGISTRY")
      set(${prefix}_NO_REGISTRY TRUE)
      set(_hubrt_expect "")
    elseif(_hubrt_expect STREQUAL "TARGET")
      set(${prefix}_TARGET "${_hubrt_arg}")
      set(_hubrt_expect "")
    elseif(_hubrt_expect STREQUAL "IDL")
      if(_hubrt_arg IN_LIST ${prefix}_GROUPS)
        message(FATAL_ERROR "hubrt_add_messages(${${prefix}_TARGET}): IDL ${_hubrt_arg} given twice")
      endif()
      set(_hubrt_group "${_hubrt_arg}")
      set(_hubrt_package hub_msgs)
      list(APPEND ${prefix}_GROUPS "${_hubrt_arg}")
      set(${prefix}_GROUP_${_hubrt_arg} "")
      set(_hubrt_expect "")
    elseif(_hubrt_expect STREQUAL "PACKAGE")
      set(_hubrt_package "${_hubrt_arg}")
      set(_hubrt_expect "")
    elseif(_hubrt_expect STREQUAL "DEPENDS")
      list(APPEND ${prefix}_DEPENDS "${_hubrt_arg}")
    elseif(_hubrt_expect STREQUAL "FILES")
      get_filename_component(_hubrt_abs "${_hubrt_arg}" ABSOLUTE)
      if(NOT EXISTS "${_hubrt_abs}")
        message(FATAL_ERROR "hubrt_add_messages(${${prefix}_TARGET}): ${_hubrt_abs} does not exist")
      endif()
      if(_hubrt_abs MATCHES "\\.msg$" AND _hubrt_group)
        list(APPEND ${prefix}_GROUP_${_hubrt_group} "${_hubrt_package}|${_hubrt_abs}")
      elseif(_hubrt_abs MATCHES "\\.idl$" AND NOT _hubrt_group)
        list(APPEND ${prefix}_IDL_FILES "${_hubrt_abs}")
      else()
        message(FATAL_ERROR "hubrt_add_messages(${${prefix}_TARGET}): ${_hubrt_arg}: .msg files go after "
                            "IDL <stem>, hand-written .idl files (test fixtures) before any IDL")
      endif()
    else()
      message(FATAL_ERROR "usage: hubrt_add_messages(TARGET <target> [IDL <stem> [PACKAGE <pkg>] FILES "
                          "<file.msg>...]... [FILES <file.idl>...] [DEPENDS <target>...] [NO_REGISTRY]); "
                          "unexpected '${_hubrt_arg}'")
    endif()
  endforeach()
  if(NOT ${prefix}_TARGET OR (NOT ${prefix}_GROUPS AND NOT ${prefix}_IDL_FILES))
    message(FATAL_ERROR "hubrt_add_messages: a TARGET and .msg files (IDL <stem> FILES ...) are needed; "
                        "got: ${ARGN}")
  endif()
  foreach(_hubrt_group IN LISTS ${prefix}_GROUPS)
    if(NOT ${prefix}_GROUP_${_hubrt_group})
      message(FATAL_ERROR "hubrt_add_messages(${${prefix}_TARGET}): IDL ${_hubrt_group} has no .msg FILES")
    endif()
  endforeach()
endmacro()

# hubrt_messages_add_registry(<target>): a static library defining hubrt::msgs::all_types() over
# every registered message target. Its source is written once all of CMakeLists.txt has run, so
# targets added later (hubs/*) are included without naming them here.
function(hubrt_messages_add_registry target)
  set(file "${CMAKE_CURRENT_BINARY_DIR}/${target}.cc")
  add_library(${target} ${HUBRT_LIBRARY_KIND} "${file}")
  target_link_libraries(${target} PUBLIC hubrt_msgs_reflect)
  # hubrt/msgs/all_command_state_pairs.h, written with the registry (for the code that handles every
  # Command/State pair: the hostile command corpus).
  set(include_dir "${CMAKE_CURRENT_BINARY_DIR}/${target}_include")
  target_include_directories(${target} PUBLIC "${include_dir}")
  if(COMMAND hubrt_target_defaults)
    hubrt_target_defaults(${target})
  endif()
  # Deferred-call arguments are expanded when the call runs, hence EVAL to bind them now.
  cmake_language(EVAL CODE "
    cmake_language(DEFER DIRECTORY [[${CMAKE_SOURCE_DIR}]]
                   CALL _hubrt_messages_write_registry [[${target}]] [[${file}]] [[${include_dir}]])")
endfunction()

function(_hubrt_messages_write_registry target file include_dir)
  get_property(targets GLOBAL PROPERTY HUBRT_MESSAGE_TARGETS)
  hubrt_messages_write_registry_source("${file}" "every hubrt_add_messages() target" ${targets})
  target_link_libraries(${target} PUBLIC ${targets})
  # Every Command/State pair with typed classes of every registered target: the plugin writes a
  # visitor per IDL file (for_each_command_state_pair_of_<stem>, <stem>_typed.h), this calls them all.
  set(includes "")
  set(calls "")
  foreach(t IN LISTS targets)
    get_target_property(t_stems ${t} HUBRT_IDL_STEMS)
    foreach(stem IN LISTS t_stems)
      string(MAKE_C_IDENTIFIER "${stem}" id)
      string(APPEND includes "#include \"${stem}_reflect.h\"\n#include \"${stem}_typed.h\"\n")
      string(APPEND calls "  for_each_command_state_pair_of_${id}(visit);\n")
    endforeach()
  endforeach()
  file(CONFIGURE OUTPUT "${include_dir}/hubrt/msgs/all_command_state_pairs.h" @ONLY CONTENT [=[
// Generated by firmware/msgs/cmake/HubrtMessages.cmake: every Command/State pair of the registered
// message targets (the types of hubrt::msgs::all_types() that have typed classes). Do not edit.
#pragma once

@includes@
namespace hubrt::msgs::typed {

// Calls visit.template operator()<CommandView, State>() for every pair, e.g.
// for_each_command_state_pair([]<class C, class S>() { ... }).
template <class Visit>
void for_each_command_state_pair(Visit&& visit) {
@calls@}

}  // namespace hubrt::msgs::typed
]=])
  # The hub_msgs .msg files the registry holds, for the check that the ROS 2 package gathers them
  # all (firmware/msgs/test: hubrt_ros2_hub_msgs_holds_every_type).
  set(hub_msgs "")
  foreach(t IN LISTS targets)
    get_target_property(entries ${t} HUBRT_MSG_ENTRIES)
    foreach(entry IN LISTS entries)
      if(entry MATCHES "^hub_msgs\\|(.*)$")
        list(APPEND hub_msgs "${CMAKE_MATCH_1}")
      endif()
    endforeach()
  endforeach()
  list(SORT hub_msgs)
  list(JOIN hub_msgs "\n" hub_msgs_text)
  file(CONFIGURE OUTPUT "${CMAKE_BINARY_DIR}/hub_msgs_registered.txt" CONTENT "${hub_msgs_text}\n" @ONLY)
endfunction()

# hubrt_messages_write_registry_source(<file> <what> <message target>...): writes <file>, the
# definition of hubrt::msgs::all_types() over the types of the given message targets (<what> says
# which, in the file's comment), and of the .msg texts those targets hold
# (generated_msg_definitions(), behind hubrt/msgs/definitions.h). hubrt_msgs_all uses it for every
# target; a board program's hub type registry (hubs/HubTypes.cmake) for the message targets its hub
# types link, so that it holds the types and texts of its own messages only.
function(hubrt_messages_write_registry_source file what)
  set(targets ${ARGN})
  set(declarations "")
  set(lists "")
  set(text_lists "")
  foreach(t IN LISTS targets)
    get_target_property(t_stems ${t} HUBRT_IDL_STEMS)
    foreach(stem IN LISTS t_stems)
      # Same mangling as the plugin's types_function_name().
      string(MAKE_C_IDENTIFIER "${stem}" id)
      string(APPEND declarations "std::span<const TypeInfo* const> types_of_${id}() noexcept;  // ${t}\n")
      string(APPEND lists "      reflected::types_of_${id}(),\n")
    endforeach()
    get_target_property(texts ${t} HUBRT_MSG_TEXTS_FUNCTION)
    if(texts)
      string(APPEND declarations "std::span<const MsgDefinition> ${texts}() noexcept;\n")
      string(APPEND text_lists "      reflected::${texts}(),\n")
    endif()
  endforeach()
  file(CONFIGURE OUTPUT "${file}" @ONLY CONTENT [=[
// Generated by firmware/msgs/cmake/HubrtMessages.cmake: the types of @what@. Do not edit.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <vector>

#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/definitions.h"

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

// Sorted by name, for msg_text()'s binary search; built once, at the first call.
std::span<const MsgDefinition> generated_msg_definitions() noexcept {
  static const std::vector<MsgDefinition> all = [] {
    std::vector<MsgDefinition> v;
    const std::vector<std::span<const MsgDefinition>> lists = {
@text_lists@    };
    for (const auto list : lists) v.insert(v.end(), list.begin(), list.end());
    std::sort(v.begin(), v.end(), [](const MsgDefinition& a, const MsgDefinition& b) { return a.ros_name < b.ros_name; });
    return v;
  }();
  return all;
}

}  // namespace hubrt::msgs
]=])
endfunction()
