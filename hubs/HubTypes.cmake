# hubrt_register_hub_type(TARGET <lib> HEADER <header> FUNCTION <qualified function>
#                         [DEVICES <kind>...])
#   Records a hub type: <lib> provides `const hubrt::hub_api::HubType& <function>() noexcept`,
#   declared in <header>. Its name is its folder's (hubs/<name>/, the name board files give).
#   DEVICES: the Linux device kinds beyond GPIO its code opens (Backend::open_can, open_modbus,
#   open_badge_reader): can, modbus, badge_reader. A program links the device libraries of its hub
#   types' kinds and no other; opening a kind not linked is a clear error (hal::LinuxBackend).
# hubrt_add_hub_type_registry(<target> [TYPES <name>...])
#   Generates the library defining hubrt::assembly::hub_types() over every recorded hub type, or
#   over the named ones only: a board's program links the hub types its board runs and no other
#   (firmware/hubd: board/<hub type>/hubd; docs/board-size.md). It also defines
#   hubrt::assembly::linux_device_libraries(): the device libraries of those hub types' DEVICES.
#   With TYPES, it also defines hubrt::msgs::all_types() over the message types those hub types
#   link (their hubrt_add_messages() targets, found through their link libraries), where a
#   subscription's `type:` is looked up (hub_api::Subscriptions): a board's program holds neither
#   the simulation's messages nor those of hub types it does not run. Its object comes before the
#   libraries at link, so hubrt_msgs_all's definition (which hub_api links for every other program)
#   is never taken into it; the board programs' tests check both (firmware/hubd).
include_guard(GLOBAL)

# hubrt_add_hub_folders(<dir> [EXCEPT <name>...])
#   Adds every folder <dir>/<hub>/ that has a CMakeLists.txt, in sorted order (the same build on
#   every machine): first each one's msg/ (its message targets, which may DEPEND on
#   hubrt_msgs_common), then the folders themselves. hubs/CMakeLists.txt adds hubs/ with it; the
#   new-hub check (tests/new_hub) a copied folder, the same way.
function(hubrt_add_hub_folders dir)
  cmake_parse_arguments(PARSE_ARGV 1 A "" "" "EXCEPT")
  file(GLOB cmakelists CONFIGURE_DEPENDS RELATIVE "${dir}" "${dir}/*/CMakeLists.txt")
  list(SORT cmakelists)
  set(hubs "")
  foreach(file IN LISTS cmakelists)
    get_filename_component(hub "${file}" DIRECTORY)
    if(NOT hub IN_LIST A_EXCEPT)
      list(APPEND hubs "${hub}")
    endif()
  endforeach()
  foreach(hub IN LISTS hubs)
    if(EXISTS "${dir}/${hub}/msg/CMakeLists.txt")
      add_subdirectory("${dir}/${hub}/msg" "${CMAKE_CURRENT_BINARY_DIR}/${hub}/msg")
    endif()
  endforeach()
  foreach(hub IN LISTS hubs)
    add_subdirectory("${dir}/${hub}" "${CMAKE_CURRENT_BINARY_DIR}/${hub}")
  endforeach()
endfunction()

# The device kinds DEVICES may name, in hal::LinuxDeviceLibraries' order.
set(HUBRT_DEVICE_KINDS can modbus badge_reader)

function(hubrt_register_hub_type)
  cmake_parse_arguments(PARSE_ARGV 0 A "" "TARGET;HEADER;FUNCTION" "DEVICES")
  if(NOT A_TARGET OR NOT A_HEADER OR NOT A_FUNCTION)
    message(FATAL_ERROR "usage: hubrt_register_hub_type(TARGET <lib> HEADER <header> FUNCTION <function> "
                        "[DEVICES <kind>...])")
  endif()
  get_filename_component(name "${CMAKE_CURRENT_SOURCE_DIR}" NAME)
  foreach(kind IN LISTS A_DEVICES)
    if(NOT kind IN_LIST HUBRT_DEVICE_KINDS)
      list(JOIN HUBRT_DEVICE_KINDS ", " known)
      message(FATAL_ERROR "hubrt_register_hub_type(${name}): unknown device kind '${kind}' "
                          "(${known}; GPIO and HTTP are in every hubd)")
    endif()
  endforeach()
  set_property(GLOBAL PROPERTY HUBRT_HUB_TYPE_DEVICES_${name} ${A_DEVICES})
  set_property(GLOBAL APPEND PROPERTY HUBRT_HUB_TYPE_NAMES ${name})
  set_property(GLOBAL APPEND PROPERTY HUBRT_HUB_TYPE_TARGETS ${A_TARGET})
  set_property(GLOBAL APPEND PROPERTY HUBRT_HUB_TYPE_HEADERS ${A_HEADER})
  set_property(GLOBAL APPEND PROPERTY HUBRT_HUB_TYPE_FUNCTIONS ${A_FUNCTION})
endfunction()

# The registered message targets (hubrt_add_messages() without NO_REGISTRY) that the targets
# `roots` link, directly or through other targets.
function(_hubrt_message_targets_of out)
  get_property(registered GLOBAL PROPERTY HUBRT_MESSAGE_TARGETS)
  set(queue ${ARGN})
  set(seen "")
  set(found "")
  while(queue)
    list(POP_FRONT queue t)
    if(NOT TARGET ${t} OR t IN_LIST seen OR t STREQUAL "hubrt_msgs_all")
      continue()
    endif()
    list(APPEND seen ${t})
    if(t IN_LIST registered)
      list(APPEND found ${t})
    endif()
    hubrt_linked_targets(${t} links)
    list(APPEND queue ${links})
  endwhile()
  set(${out} ${found} PARENT_SCOPE)
endfunction()

function(hubrt_add_hub_type_registry target)
  cmake_parse_arguments(PARSE_ARGV 1 A "" "" "TYPES")
  get_property(names GLOBAL PROPERTY HUBRT_HUB_TYPE_NAMES)
  get_property(all_targets GLOBAL PROPERTY HUBRT_HUB_TYPE_TARGETS)
  get_property(headers GLOBAL PROPERTY HUBRT_HUB_TYPE_HEADERS)
  get_property(functions GLOBAL PROPERTY HUBRT_HUB_TYPE_FUNCTIONS)
  set(wanted ${names})
  if(A_TYPES)
    set(wanted ${A_TYPES})
  endif()
  set(targets "")
  set(includes "")
  set(entries "")
  set(kinds "")
  foreach(type IN LISTS wanted)
    list(FIND names "${type}" i)
    if(i LESS 0)
      list(JOIN names ", " known)
      message(FATAL_ERROR "hubrt_add_hub_type_registry(${target}): no hub type '${type}' (known: ${known})")
    endif()
    list(GET all_targets ${i} lib)
    list(GET headers ${i} header)
    list(GET functions ${i} function)
    list(APPEND targets ${lib})
    string(APPEND includes "#include \"${header}\"\n")
    string(APPEND entries "      &${function}(),\n")
    get_property(type_kinds GLOBAL PROPERTY HUBRT_HUB_TYPE_DEVICES_${type})
    list(APPEND kinds ${type_kinds})
  endforeach()
  # The device libraries of those kinds, in LinuxDeviceLibraries' order (designated initialisers),
  # every member named, null where not linked (no missing-initialiser warnings). Per kind: its
  # member, library, header and opener (open_libmodbus is overloaded, with a clock: the lambda picks
  # the one without).
  set(kind_can open_can hubrt_hal_socketcan hubrt/hal/socketcan/open_socketcan.h
      "&hal::socketcan::open_socketcan")
  set(kind_modbus open_modbus hubrt_hal_libmodbus hubrt/hal/libmodbus/open_libmodbus.h
      "[](const hal::ModbusConfig& config) { return hal::libmodbus::open_libmodbus(config)\; }")
  set(kind_badge_reader open_badge_reader hubrt_hal_rfid hubrt/hal/rfid/open_badge_reader.h
      "&hal::rfid::open_badge_reader")
  set(device_libs "")
  set(device_includes "")
  set(device_entries "")
  foreach(kind IN LISTS HUBRT_DEVICE_KINDS)
    list(GET kind_${kind} 0 member)
    if(kind IN_LIST kinds)
      list(GET kind_${kind} 1 library)
      list(GET kind_${kind} 2 header)
      list(GET kind_${kind} 3 opener)
      list(APPEND device_libs ${library})
      string(APPEND device_includes "#include \"${header}\"\n")
      string(APPEND device_entries "      .${member} = ${opener},\n")
    else()
      string(APPEND device_entries "      .${member} = nullptr,\n")
    endif()
  endforeach()
  set(source ${CMAKE_CURRENT_BINARY_DIR}/${target}.cc)
  file(GENERATE OUTPUT ${source} CONTENT "// Generated by hubs/HubTypes.cmake: the hub types built into this program.
#include <array>
#include <string_view>

#include \"hubrt/assembly/hub_types.h\"
#include \"hubrt/assembly/linux_device_libraries.h\"
${includes}${device_includes}
namespace hubrt::assembly {

std::span<const hub_api::HubType* const> hub_types() noexcept {
  static const auto types = std::to_array<const hub_api::HubType*>({
${entries}  });
  return types;
}

const hub_api::HubType* find_hub_type(std::string_view name) noexcept {
  for (const hub_api::HubType* type : hub_types()) {
    if (type->name() == name) return type;
  }
  return nullptr;
}

hal::LinuxDeviceLibraries linux_device_libraries() noexcept {
  return hal::LinuxDeviceLibraries{
${device_entries}  };
}

}  // namespace hubrt::assembly
")
  set(sources ${source})
  if(A_TYPES)
    _hubrt_message_targets_of(message_targets ${targets})
    list(JOIN wanted ", " type_names)
    set(messages_source ${CMAKE_CURRENT_BINARY_DIR}/${target}_messages.cc)
    hubrt_messages_write_registry_source(${messages_source} "the message targets hub type(s) ${type_names} link"
                                         ${message_targets})
    list(APPEND sources ${messages_source})
  endif()
  # An object library: the registry's object goes into the program itself, so the libraries that
  # call hub_types() (the composition root) find it wherever the linker meets them.
  add_library(${target} OBJECT ${sources})
  # The declaration of hub_types() is the composition root's (hubrt/assembly/hub_types.h); the
  # registry needs only that header, not the library (which itself uses the registry).
  target_include_directories(${target} PUBLIC ${HUBRT_SOURCE_DIR}/firmware/assembly/include)
  target_link_libraries(${target} PUBLIC ${targets} hubrt_hal_linux ${device_libs} ${message_targets})
endfunction()
