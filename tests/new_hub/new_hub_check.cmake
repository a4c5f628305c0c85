# cmake -DSOURCE=<hubrt source> -DBUILD=<hubrt build> -DWORK=<scratch dir> -DGENERATOR=<g>
#       -DC_COMPILER=<cc> -DCXX_COMPILER=<c++> -DLAUNCHER=<ccache or empty> -DBUILD_TYPE=<type>
#       -DC_FLAGS=<...> -DCXX_FLAGS=<...> [-DEXE_LINKER_FLAGS=<...>] [-DSHARED_LINKER_FLAGS=<...>]
#       -P new_hub_check.cmake
# The new-hub check (docs/new-hub.md, "Shown by doing it"): what a newcomer does, done to a
# throw-away hub type. hubs/signal_lamp is copied into a new folder and renamed (signal_lamp ->
# signal_strobe, Lamp -> Strobe, lamp -> strobe: file names and contents) — nothing outside that
# folder is written or edited — then a small project builds that folder against the already built
# hubrt (tests/new_hub/CMakeLists.txt: the hub folder discovery and CMake functions of hubs/), with
# a hubd and a hubctl that hold it, and runs the folder's tests: its logic tests, the hubd test and
# hubctl conformance in both layouts. Everything is written under WORK, never into the source tree.
cmake_minimum_required(VERSION 3.25)
foreach(var SOURCE BUILD WORK GENERATOR C_COMPILER CXX_COMPILER)
  if(NOT ${var})
    message(FATAL_ERROR "new_hub_check.cmake: -D${var}=... missing")
  endif()
endforeach()

# The copy, renamed: a hub type the hubrt build has never seen.
set(tree "${WORK}/tree")
set(hub "${tree}/hubs/signal_strobe")
file(REMOVE_RECURSE "${WORK}")
file(GLOB_RECURSE files RELATIVE "${SOURCE}/hubs/signal_lamp" "${SOURCE}/hubs/signal_lamp/*")
list(LENGTH files count)
if(count LESS 10)
  message(FATAL_ERROR "hubs/signal_lamp: only ${count} files found")
endif()
foreach(file IN LISTS files)
  file(READ "${SOURCE}/hubs/signal_lamp/${file}" text)
  foreach(pair "LAMP;STROBE" "Lamp;Strobe" "lamp;strobe")
    list(GET pair 0 from)
    list(GET pair 1 to)
    string(REPLACE "${from}" "${to}" text "${text}")
    string(REPLACE "${from}" "${to}" file "${file}")
  endforeach()
  file(WRITE "${hub}/${file}" "${text}")
endforeach()
file(GLOB_RECURSE written RELATIVE "${WORK}" "${WORK}/*")
foreach(path IN LISTS written)
  if(NOT path MATCHES "^tree/hubs/signal_strobe/")
    message(FATAL_ERROR "the check wrote ${path} outside the new hub's folder")
  endif()
endforeach()

function(run what)
  string(TIMESTAMP started "%s")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(TIMESTAMP ended "%s")
  math(EXPR seconds "${ended} - ${started}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "new hub check: ${what} failed (${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "${what}: ${seconds} s")
  set(output "${out}" PARENT_SCOPE)
endfunction()

set(build "${WORK}/build")
string(TOUPPER "${BUILD_TYPE}" BUILD_TYPE_UPPER)
run("configure" "${CMAKE_COMMAND}" -S "${SOURCE}/tests/new_hub" -B "${build}" -G "${GENERATOR}"
    "-DCMAKE_C_COMPILER=${C_COMPILER}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}"
    "-DCMAKE_C_COMPILER_LAUNCHER=${LAUNCHER}" "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}"
    "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}" "-DCMAKE_C_FLAGS_${BUILD_TYPE_UPPER}=${C_FLAGS}"
    "-DCMAKE_CXX_FLAGS_${BUILD_TYPE_UPPER}=${CXX_FLAGS}" "-DHUBRT_BUILD_DIR=${BUILD}" "-DHUB_TREE=${tree}"
    # The hubrt build's linker too (lld in clang's builds): GNU ld took 14 s for the new hubctl
    # alone, most of the check's build.
    "-DCMAKE_EXE_LINKER_FLAGS=${EXE_LINKER_FLAGS}" "-DCMAKE_SHARED_LINKER_FLAGS=${SHARED_LINKER_FLAGS}"
    "-DCMAKE_MODULE_LINKER_FLAGS=${SHARED_LINKER_FLAGS}")
run("build" "${CMAKE_COMMAND}" --build "${build}")
run("tests" "${CMAKE_CTEST_COMMAND}" --test-dir "${build}" --output-on-failure -j 2)
message("${output}")
# The folder's three test programs ran: the logic tests (a unit program: one CTest test for the
# whole program, toolchain/cmake/HubrtTargets.cmake), the hubd test, conformance in both layouts.
foreach(expected "hubrt_signal_strobe_test" "HubdStrobeTest" "StrobeConformanceTest.PassesEveryCheck/.node_type"
                 "StrobeConformanceTest.PassesEveryCheck/.hub")
  if(NOT output MATCHES "${expected}")
    message(FATAL_ERROR "new hub check: no test ${expected} ran")
  endif()
endforeach()
if(NOT output MATCHES "100% tests passed")
  message(FATAL_ERROR "new hub check: not every test passed")
endif()
