# Fails when the program BINARY, stripped as the board packages ship it, is larger than MAX_BYTES.
# States the figure either way (ctest --output-on-failure, or -V), so the log of every cross build
# says how large the board hubd is. The stripped copy goes to STRIPPED (the build tree keeps its
# symbols for debugging).
#   cmake -DBINARY=<program> -DSTRIP=<strip> -DSTRIPPED=<file> -DMAX_BYTES=<n> [-DAIM_BYTES=<n>]
#         -P check_stripped_size.cmake
if(NOT BINARY OR NOT STRIP OR NOT STRIPPED OR NOT MAX_BYTES)
  message(FATAL_ERROR "usage: cmake -DBINARY=<program> -DSTRIP=<strip> -DSTRIPPED=<file> -DMAX_BYTES=<n> "
                      "[-DAIM_BYTES=<n>] -P check_stripped_size.cmake")
endif()
execute_process(COMMAND "${STRIP}" -o "${STRIPPED}" "${BINARY}" ERROR_VARIABLE errors RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${STRIP} -o ${STRIPPED} ${BINARY} failed: ${errors}")
endif()
file(SIZE "${STRIPPED}" bytes)
math(EXPR kilobytes "(${bytes} + 500) / 1000")
set(figure "${BINARY} stripped: ${bytes} bytes (${kilobytes} kB); bound ${MAX_BYTES}")
if(AIM_BYTES)
  string(APPEND figure ", aim ${AIM_BYTES}")
endif()
if(bytes GREATER MAX_BYTES)
  message(FATAL_ERROR "${figure}: larger than the bound (what grew: nm --size-sort -C -S on the unstripped "
                      "program; docs/board-size.md)")
endif()
message(STATUS "${figure}")
