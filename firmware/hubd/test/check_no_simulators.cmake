# Fails when the program BINARY contains code of the fake backend or the simulators: symbols in
# namespace hubrt::hal::fake (device simulators, Modbus servers, virtual CAN) or hubrt::sim (the sim
# bridge, the station model). The board build of hubd must link none of them (firmware/hubd,
# assembly/simulation.h); the same check on the development hubd must fail (WILL_FAIL), which shows
# the patterns still match what the simulators are called.
#   cmake -DBINARY=<program> -DNM=<nm> -P check_no_simulators.cmake
if(NOT BINARY OR NOT NM)
  message(FATAL_ERROR "usage: cmake -DBINARY=<program> -DNM=<nm> -P check_no_simulators.cmake")
endif()
execute_process(COMMAND "${NM}" --demangle --defined-only "${BINARY}"
                OUTPUT_VARIABLE symbols ERROR_VARIABLE errors RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${NM} ${BINARY} failed: ${errors}")
endif()
# string(FIND), not a regular expression over the whole listing: a sanitizer build's hubd has
# ~56,000 symbols, and REGEX MATCHALL with a line pattern took over a minute on a loaded machine.
foreach(namespace "hubrt::hal::fake::" "hubrt::sim::")
  string(FIND "${symbols}" "${namespace}" at)
  if(NOT at EQUAL -1)
    math(EXPR from "${at} - 60")
    if(from LESS 0)
      set(from 0)
    endif()
    string(SUBSTRING "${symbols}" ${from} 200 around)
    message(FATAL_ERROR "${BINARY} links code of the fake backend or the simulators (${namespace}), e.g. near: ${around}")
  endif()
endforeach()
message(STATUS "${BINARY}: no symbol of hubrt::hal::fake or hubrt::sim")
