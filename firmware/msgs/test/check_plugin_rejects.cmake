# cmake -DIDLC=... -DPLUGIN=... -DIDL=unsupported.idl -DOUT=<dir> -P check_plugin_rejects.cmake
# Runs idlc with the reflection plugin on IDL it must refuse and checks that it fails, names every
# construct at its line, and leaves no half-written tables behind.
file(REMOVE_RECURSE "${OUT}")
file(MAKE_DIRECTORY "${OUT}")
execute_process(COMMAND "${IDLC}" -l "${PLUGIN}" -x final -o "${OUT}" "${IDL}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 30)
set(all "${out}${err}")
if(rc EQUAL 0)
  message(FATAL_ERROR "idlc accepted ${IDL}; output:\n${all}")
endif()
foreach(expected
    "unsupported.idl:4:3: enum 'Color' is not supported"
    "unsupported.idl:8:[0-9]+: bad::Everything.short_texts: arrays of bounded strings are not supported"
    "unsupported.idl:9:[0-9]+: bad::Everything.maybe: @optional and @external members are not supported"
    "unsupported.idl:10:[0-9]+: bad::Everything.nested: sequences of sequences are not supported"
    "unsupported.idl:11:[0-9]+: bad::Everything.grid: multi-dimensional arrays are not supported")
  if(NOT all MATCHES "${expected}")
    message(FATAL_ERROR "expected a message matching '${expected}'; idlc said:\n${all}")
  endif()
endforeach()
file(GLOB leftovers "${OUT}/*")
if(leftovers)
  message(FATAL_ERROR "failed generation left files behind: ${leftovers}")
endif()
message(STATUS "idlc refused ${IDL} as expected:\n${all}")
