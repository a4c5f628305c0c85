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
string(REGEX MATCHALL "[^\n]*hubrt::(hal::fake|sim)::[^\n]*" found "${symbols}")
list(LENGTH found count)
if(count GREATER 0)
  list(GET found 0 first)
  message(FATAL_ERROR "${BINARY} links ${count} symbols of the fake backend or the simulators, e.g. ${first}")
endif()
message(STATUS "${BINARY}: no symbol of hubrt::hal::fake or hubrt::sim")
