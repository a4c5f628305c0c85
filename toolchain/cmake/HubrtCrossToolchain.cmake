# Shared body of the cross toolchain files (aarch64-linux-gnu.cmake, arm-linux-gnueabihf.cmake).
# The caller sets HUBRT_TARGET_TRIPLET, HUBRT_TARGET_DEB_ARCH, HUBRT_TARGET_QEMU and
# CMAKE_SYSTEM_PROCESSOR, then includes this file.
#
# Compiler, libc and libstdc++ come from Debian's cross toolchain (g++-<triplet>, files under
# /usr/<triplet>); every other library comes from the target sysroot that toolchain/prepare-target
# unpacks from the target architecture's .debs. Target binaries (tests, gtest discovery, try_run)
# run under qemu-user with that sysroot as their root for libraries.
#
# Sysroot location, first that is set: -DHUBRT_SYSROOT=<dir>; environment HUBRT_SYSROOTS (the
# folder holding <arch>/ sysroots, as for prepare-target); <repo>/toolchain/.sysroots/<arch>.

set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_LIBRARY_ARCHITECTURE ${HUBRT_TARGET_TRIPLET})
set(CMAKE_C_COMPILER ${HUBRT_TARGET_TRIPLET}-gcc)
set(CMAKE_CXX_COMPILER ${HUBRT_TARGET_TRIPLET}-g++)

if(NOT HUBRT_SYSROOT)
  if(DEFINED ENV{HUBRT_SYSROOTS})
    if(NOT IS_ABSOLUTE "$ENV{HUBRT_SYSROOTS}")
      message(FATAL_ERROR "HUBRT_SYSROOTS must be an absolute path (is '$ENV{HUBRT_SYSROOTS}')")
    endif()
    set(_hubrt_sysroot "$ENV{HUBRT_SYSROOTS}/${HUBRT_TARGET_DEB_ARCH}")
  else()
    get_filename_component(_hubrt_sysroot "${CMAKE_CURRENT_LIST_DIR}/../.sysroots/${HUBRT_TARGET_DEB_ARCH}"
                           ABSOLUTE)
  endif()
  set(HUBRT_SYSROOT "${_hubrt_sysroot}" CACHE PATH "Target sysroot made by toolchain/prepare-target")
endif()
# try_compile projects re-read this file without the cache: hand them the resolved path.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES HUBRT_SYSROOT)
if(NOT EXISTS "${HUBRT_SYSROOT}/.hubrt-sysroot")
  message(FATAL_ERROR "No ${HUBRT_TARGET_DEB_ARCH} sysroot at ${HUBRT_SYSROOT}: "
                      "run toolchain/prepare-target ${HUBRT_TARGET_DEB_ARCH} (or set -DHUBRT_SYSROOT).")
endif()

# Libraries, headers and CMake packages from the sysroot and the cross toolchain only; programs
# (idlc, pkg-config) from the host.
set(CMAKE_FIND_ROOT_PATH "${HUBRT_SYSROOT}" /usr/${HUBRT_TARGET_TRIPLET})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# Debian ships no <triplet>-pkg-config wrapper: point the host pkg-config at the sysroot's .pc files.
set(ENV{PKG_CONFIG_LIBDIR}
    "${HUBRT_SYSROOT}/usr/lib/${HUBRT_TARGET_TRIPLET}/pkgconfig:${HUBRT_SYSROOT}/usr/share/pkgconfig")
set(ENV{PKG_CONFIG_SYSROOT_DIR} "${HUBRT_SYSROOT}")
set(ENV{PKG_CONFIG_PATH} "")

# The cross compiler knows nothing of the sysroot: arch-specific headers (dds/features.h) live in
# <sysroot>/usr/include/<triplet>, and the sysroot must come before the host's /usr/include, which
# Debian's cross gcc searches last. Shared libraries pull in others (libddsc -> libssl,
# libiceoryx_*): the linker finds those through rpath-link (bookworm still ships some under /lib).
# STANDARD_INCLUDE_DIRECTORIES / STANDARD_LIBRARIES rather than CMAKE_<LANG>_FLAGS_INIT, so that
# a -DCMAKE_CXX_FLAGS=... on the command line cannot drop them.
set(_hubrt_sysroot_includes "${HUBRT_SYSROOT}/usr/include/${HUBRT_TARGET_TRIPLET}" "${HUBRT_SYSROOT}/usr/include")
set(_hubrt_rpath_link
    "-Wl,-rpath-link,${HUBRT_SYSROOT}/usr/lib/${HUBRT_TARGET_TRIPLET} -Wl,-rpath-link,${HUBRT_SYSROOT}/lib/${HUBRT_TARGET_TRIPLET}")
foreach(_lang C CXX)
  set(CMAKE_${_lang}_STANDARD_INCLUDE_DIRECTORIES ${_hubrt_sysroot_includes})
  set(CMAKE_${_lang}_STANDARD_LIBRARIES "${_hubrt_rpath_link}")
endforeach()

find_program(HUBRT_QEMU_USER ${HUBRT_TARGET_QEMU})
if(NOT HUBRT_QEMU_USER)
  message(FATAL_ERROR "${HUBRT_TARGET_QEMU} not found: run toolchain/prepare-target ${HUBRT_TARGET_DEB_ARCH}.")
endif()
# -L: the sysroot is where the emulated dynamic loader and libraries are found. Its libc comes from
# the same release as the cross toolchain's, so binaries linked against the latter run with it.
set(CMAKE_CROSSCOMPILING_EMULATOR "${HUBRT_QEMU_USER};-L;${HUBRT_SYSROOT}")
