# What a hub type builds against, exported from the build tree: a project that includes
# <build>/hubrt-build/HubrtBuildConfig.cmake gets this build's libraries as imported targets (same
# names), its settings (sanitizers, shared libraries, warnings) and hubrt's own CMake functions
# (hubrt_add_library, hubrt_add_test, hubrt_add_messages with this build's generator and idlc
# plugin, hubrt_register_hub_type, hubrt_add_hub_folders), so that a hub folder builds there with
# the same CMakeLists.txt it has under hubs/. tests/new_hub builds a copied hub folder that way,
# without configuring or building this project again.
#
#   hubrt_export_build_tree(): call once from the top-level CMakeLists.txt, at its end.
include_guard(GLOBAL)

# Every target defined in `dir` and the directories below it.
function(_hubrt_targets_below dir out)
  get_property(targets DIRECTORY "${dir}" PROPERTY BUILDSYSTEM_TARGETS)
  get_property(subdirs DIRECTORY "${dir}" PROPERTY SUBDIRECTORIES)
  foreach(sub IN LISTS subdirs)
    _hubrt_targets_below("${sub}" below)
    list(APPEND targets ${below})
  endforeach()
  set(${out} ${targets} PARENT_SCOPE)
endfunction()

# The libraries that can be exported: not one whose interface names a program of this build (its
# path, $<TARGET_FILE:...>, e.g. the station's test processes), nor one that links such a library.
function(_hubrt_exportable_libraries out)
  _hubrt_targets_below("${PROJECT_SOURCE_DIR}" all)
  set(libraries "")
  set(refused "")
  foreach(t IN LISTS all)
    get_target_property(type ${t} TYPE)
    if(NOT type MATCHES "^(STATIC|SHARED|MODULE|OBJECT|INTERFACE)_LIBRARY$")
      continue()
    endif()
    get_target_property(definitions ${t} INTERFACE_COMPILE_DEFINITIONS)
    if(definitions MATCHES "TARGET_FILE")
      list(APPEND refused ${t})
    else()
      list(APPEND libraries ${t})
    endif()
  endforeach()
  set(changed TRUE)
  while(changed)
    set(changed FALSE)
    foreach(t IN LISTS libraries)
      hubrt_linked_targets(${t} links)
      foreach(link IN LISTS links)
        if(link IN_LIST refused)
          list(REMOVE_ITEM libraries ${t})
          list(APPEND refused ${t})
          set(changed TRUE)
          break()
        endif()
      endforeach()
    endforeach()
  endwhile()
  set(${out} ${libraries} PARENT_SCOPE)
endfunction()

function(hubrt_export_build_tree)
  cmake_language(DEFER DIRECTORY "${PROJECT_SOURCE_DIR}" CALL _hubrt_export_build_tree)
endfunction()

function(_hubrt_export_build_tree)
  set(dir "${CMAKE_BINARY_DIR}/hubrt-build")
  _hubrt_exportable_libraries(libraries)
  export(TARGETS ${libraries} FILE "${dir}/hubrt-targets.cmake")
  get_property(plugin GLOBAL PROPERTY HUBRT_IDLC_REFLECT_PLUGIN)
  get_property(msg2idl GLOBAL PROPERTY HUBRT_MSG2IDL)
  file(GENERATE OUTPUT "${dir}/HubrtBuildConfig.cmake" CONTENT "\
# Written by the hubrt build (toolchain/cmake/HubrtExport.cmake): this build's libraries and
# settings, and hubrt's CMake functions, for a project that builds a hub folder against them.
# Configure that project with this build's compilers and flags (tests/new_hub does).
set(HUBRT_SOURCE_DIR \"${PROJECT_SOURCE_DIR}\")
set(HUBRT_BUILD_DIR \"${CMAKE_BINARY_DIR}\")
set(HUBRT_SANITIZE \"${HUBRT_SANITIZE}\" CACHE STRING \"\" FORCE)
set(HUBRT_SHARED_LIBS ${HUBRT_SHARED_LIBS} CACHE BOOL \"\" FORCE)
set(HUBRT_WERROR ${HUBRT_WERROR} CACHE BOOL \"\" FORCE)
# A hub folder's library and tests compiled as they are in this build, so that a clash of names
# shows here too.
set(HUBRT_UNITY_TESTS ${HUBRT_UNITY_TESTS} CACHE BOOL \"\" FORCE)
set(HUBRT_UNITY_LIBRARIES ${HUBRT_UNITY_LIBRARIES} CACHE BOOL \"\" FORCE)
set(HUBRT_BUILD_TESTS ON CACHE BOOL \"\" FORCE)
set(HUBRT_IDLC_REFLECT_PLUGIN \"${plugin}\" CACHE FILEPATH \"\" FORCE)
set(HUBRT_MSG2IDL \"${msg2idl}\" CACHE FILEPATH \"\" FORCE)
list(APPEND CMAKE_MODULE_PATH \"${PROJECT_SOURCE_DIR}/toolchain/cmake\")
include(HubrtTargets)
include(HubrtDependencies)
enable_testing()
find_package(GTest REQUIRED)
include(GoogleTest)
include(\"\${CMAKE_CURRENT_LIST_DIR}/hubrt-targets.cmake\")
include(\"${PROJECT_SOURCE_DIR}/firmware/msgs/cmake/HubrtMessages.cmake\")
hubrt_messages_setup_plugin()
include(\"${PROJECT_SOURCE_DIR}/hubs/HubTypes.cmake\")
")
endfunction()
