# Fails when the program BINARY needs a library matching LIBRARIES (an ELF NEEDED entry). By
# default libcpp-httplib: hubd loads the HTTP client module hubrt-http.so only when its board opens
# an HTTP device (hal/linux/http), so that a hub without one does not map cpp-httplib nor run the
# OpenSSL initialisation Debian's build of it does at load time (~2 MB of resident memory in every
# hubd, docs/benchmarks.md). Each use has a control that must fail (WILL_FAIL: the module; for the
# device libraries, hubd_board), which shows the pattern still matches the library's name.
# The program's own shared libraries (a HUBRT_SHARED_LIBS build) are looked at with it.
# LIBRARIES: another pattern, e.g. the device libraries a board's program links only for hub types
# that open such devices (hubs/HubTypes.cmake, DEVICES).
#   cmake -DBINARY=<program> -DREADELF=<readelf> [-DLIBRARIES=<regex>] -P check_libraries_not_needed.cmake
if(NOT BINARY OR NOT READELF)
  message(FATAL_ERROR "usage: cmake -DBINARY=<program> -DREADELF=<readelf> [-DLIBRARIES=<regex>] "
                      "-P check_libraries_not_needed.cmake")
endif()
if(NOT LIBRARIES)
  set(LIBRARIES "libcpp-httplib")
endif()
include(${CMAKE_CURRENT_LIST_DIR}/program_files.cmake)
hubrt_program_files("${BINARY}" "${READELF}" files)
foreach(file IN LISTS files)
  execute_process(COMMAND "${READELF}" --dynamic "${file}"
                  OUTPUT_VARIABLE dynamic ERROR_VARIABLE errors RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${READELF} --dynamic ${file} failed: ${errors}")
  endif()
  string(REGEX MATCHALL "\\(NEEDED\\)[^\n]*\\[[^]\n]*\\]" needed "${dynamic}")
  if(NOT needed)
    message(FATAL_ERROR "${file}: no NEEDED entry found (not a dynamically linked program?)")
  endif()
  foreach(entry IN LISTS needed)
    if(entry MATCHES "${LIBRARIES}")
      message(FATAL_ERROR "${file} needs a library it should not (${LIBRARIES}): ${entry}")
    endif()
  endforeach()
endforeach()
list(LENGTH files count)
message(STATUS "${BINARY} (${count} files with its own libraries): no NEEDED entry for ${LIBRARIES}")
