# Fails when the program BINARY contains code of the fake backend or the simulators: symbols in
# namespace hubrt::hal::fake (device simulators, Modbus servers, virtual CAN) or hubrt::sim (the sim
# bridge, the station model). The board build of hubd must link none of them (firmware/hubd,
# assembly/simulation.h); the same check on the development hubd must fail (WILL_FAIL), which shows
# the patterns still match what the simulators are called. The program's own shared libraries
# (a HUBRT_SHARED_LIBS build) are looked at with it.
#   cmake -DBINARY=<program> -DNM=<nm> -DREADELF=<readelf> -P check_no_simulators.cmake
if(NOT BINARY OR NOT NM OR NOT READELF)
  message(FATAL_ERROR "usage: cmake -DBINARY=<program> -DNM=<nm> -DREADELF=<readelf> -P check_no_simulators.cmake")
endif()
include(${CMAKE_CURRENT_LIST_DIR}/program_files.cmake)
hubrt_program_files("${BINARY}" "${READELF}" files)
# Each file's listing is searched on its own: a sanitizer build's hubd and its libraries list ~32 MB
# of symbols, and gathering them into one string before searching took most of this check's time.
# string(FIND), not a regular expression: REGEX MATCHALL with a line pattern over such a listing
# took over a minute on a loaded machine.
foreach(file IN LISTS files)
  execute_process(COMMAND "${NM}" --demangle --defined-only "${file}"
                  OUTPUT_VARIABLE symbols ERROR_VARIABLE errors RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${NM} ${file} failed: ${errors}")
  endif()
  foreach(namespace "hubrt::hal::fake::" "hubrt::sim::")
    string(FIND "${symbols}" "${namespace}" at)
    if(NOT at EQUAL -1)
      math(EXPR from "${at} - 60")
      if(from LESS 0)
        set(from 0)
      endif()
      string(SUBSTRING "${symbols}" ${from} 200 around)
      message(FATAL_ERROR "${BINARY} links code of the fake backend or the simulators (${namespace}) in "
                          "${file}, e.g. near: ${around}")
    endif()
  endforeach()
endforeach()
list(LENGTH files count)
message(STATUS "${BINARY} (${count} files with its own libraries): no symbol of hubrt::hal::fake or hubrt::sim")
