# Depends of a board package, derived the way Debian derives it: dpkg-shlibdeps on the binaries as
# they are packed. Runs inside cpack (CPACK_PRE_BUILD_SCRIPTS of HubrtBoardPackage.cmake), after
# the staging install and before the .deb is made, and sets CPACK_DEBIAN_PACKAGE_DEPENDS.
#
# The target's libraries live in the sysroot, not in the host's dpkg database, so dpkg-shlibdeps
# treats the sysroot as a package build tree (-S): toolchain/prepare-target writes every sysroot
# package's symbols and shlibs files into <sysroot>/DEBIAN/, where dpkg-shlibdeps looks for them.
# Per-symbol minimum versions come from the symbols files, as in a Debian build.
#
# Inputs (cpack-settings.cmake): HUBRT_PKG_SYSROOT, HUBRT_PKG_DEB_ARCH, HUBRT_PKG_BINARIES (paths
# relative to the package root), HUBRT_PKG_DEB_DEPENDS_EXTRA (packages the maintainer scripts use).

foreach(var CPACK_TEMPORARY_DIRECTORY HUBRT_PKG_SYSROOT HUBRT_PKG_DEB_ARCH HUBRT_PKG_BINARIES)
  if(NOT ${var})
    message(FATAL_ERROR "DebDepends.cmake: ${var} is not set (run through cpack with HubrtBoardPackage)")
  endif()
endforeach()
foreach(file symbols shlibs)
  if(NOT EXISTS "${HUBRT_PKG_SYSROOT}/DEBIAN/${file}")
    message(FATAL_ERROR "${HUBRT_PKG_SYSROOT}/DEBIAN/${file} is missing: run toolchain/prepare-target "
                        "${HUBRT_PKG_DEB_ARCH} (it collects the sysroot packages' dependency information)")
  endif()
endforeach()
find_program(HUBRT_DPKG_SHLIBDEPS dpkg-shlibdeps)
if(NOT HUBRT_DPKG_SHLIBDEPS)
  message(FATAL_ERROR "dpkg-shlibdeps not found: install dpkg-dev (toolchain/install-deps)")
endif()

set(_binaries "")
foreach(binary IN LISTS HUBRT_PKG_BINARIES)
  set(_path "${CPACK_TEMPORARY_DIRECTORY}/${binary}")
  if(NOT EXISTS "${_path}")
    message(FATAL_ERROR "DebDepends.cmake: ${binary} is not in the package (${_path})")
  endif()
  list(APPEND _binaries "${_path}")
endforeach()

# dpkg-shlibdeps wants to run in a source package's folder (debian/control).
set(_work "${CPACK_TOPLEVEL_DIRECTORY}/shlibdeps")
file(REMOVE_RECURSE "${_work}")
file(MAKE_DIRECTORY "${_work}/debian")
file(WRITE "${_work}/debian/control" "")
execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env "DEB_HOST_ARCH=${HUBRT_PKG_DEB_ARCH}"
          "${HUBRT_DPKG_SHLIBDEPS}" -O "-S${HUBRT_PKG_SYSROOT}" ${_binaries}
  WORKING_DIRECTORY "${_work}"
  OUTPUT_VARIABLE _out ERROR_VARIABLE _err RESULT_VARIABLE _result)
# Its warning that the binaries are not in a package build tree is expected: they are in CPack's.
string(REGEX REPLACE "[^\n]*binaries to analyze should already be installed[^\n]*\n?" "" _err "${_err}")
if(NOT _result EQUAL 0 OR NOT _out MATCHES "shlibs:Depends=([^\n]*)")
  message(FATAL_ERROR "dpkg-shlibdeps failed (exit ${_result}):\n${_err}${_out}")
endif()
set(_depends "${CMAKE_MATCH_1}")
if(_err)
  message(WARNING "dpkg-shlibdeps:\n${_err}")
endif()
foreach(extra IN LISTS HUBRT_PKG_DEB_DEPENDS_EXTRA)
  string(APPEND _depends ", ${extra}")
endforeach()
set(CPACK_DEBIAN_PACKAGE_DEPENDS "${_depends}")
message(STATUS "Depends: ${CPACK_DEBIAN_PACKAGE_DEPENDS}")
