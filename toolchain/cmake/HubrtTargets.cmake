# Helpers every folder uses, so that warnings, sanitizers and test registration stay uniform.

set(HUBRT_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
    -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual -Wimplicit-fallthrough)
set(HUBRT_C_WARNINGS -Wall -Wextra)

if(HUBRT_SANITIZE)
  string(REPLACE "," ";" _hubrt_sanitizers "${HUBRT_SANITIZE}")
  set(_hubrt_san_flags -fsanitize=${HUBRT_SANITIZE} -fno-omit-frame-pointer)
  if("undefined" IN_LIST _hubrt_sanitizers)
    list(APPEND _hubrt_san_flags -fno-sanitize-recover=undefined)
    # Neither compiler says so in a macro (hubrt/base/sanitizers.h has the other two).
    add_compile_definitions(HUBRT_SANITIZE_UNDEFINED=1)
  endif()
  add_compile_options(${_hubrt_san_flags})
  add_link_options(${_hubrt_san_flags})
  if("address" IN_LIST _hubrt_sanitizers AND CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    # clang's default (=runtime) puts in every function with locals a fake-stack branch that only
    # ASAN_OPTIONS=detect_stack_use_after_return=1 takes; nothing here sets it (clang 14's runtime
    # default is off), so the code was compiled and never run. Library objects 0.956x, test
    # objects 1.016x (noise) of the CPU without it (docs/ci.md, "Less instrumentation in the tests' own code").
    add_compile_options(-fsanitize-address-use-after-return=never)
  endif()
  # The test programs' own sources (hubrt_add_test; not the fakes, simulators and support
  # libraries they link, and nothing that ships) leave out the UBSan checks that were most of
  # UBSan's cost there, at -O0 about a fifth of a test object's compile: null and alignment (a
  # pointer or reference used; ASan reports a dereference of null or freed memory itself), vptr
  # (the dynamic type at a downcast or member call) and function (an indirect call's type). The
  # code under test keeps every check; so do the other UBSan checks (overflow, shift, bounds,
  # enum, bool, ...) in the tests. docs/ci.md, "Less instrumentation in the tests' own code".
  if("undefined" IN_LIST _hubrt_sanitizers AND CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    set(_hubrt_test_san_flags -fno-sanitize=null,alignment,vptr,function)
  endif()
endif()

# HUBRT_BOARD_LTO (top-level CMakeLists.txt): IR in every object, no LTO at link except for a target
# whose property HUBRT_LTO is set (firmware/hubd: hubd_board). GCC's manual, "Optimize Options":
# fat objects (-ffat-lto-objects) "contain both the intermediate language and the object code", and
# with -fno-lto at link "no interprocedural optimizations are applied": the object code is linked as
# without LTO. Without -fno-lto the linker plugin optimises every program that links such objects
# (the options are recorded in them: hubd_board linked with neither flag came out LTO-sized), and
# with -fno-lto anywhere on the link line there is no LTO even with -flto after it (seen with
# GCC 12), so each target gets exactly one of the two (docs/board-size.md).
if(HUBRT_BOARD_LTO)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    message(FATAL_ERROR "HUBRT_BOARD_LTO needs GCC (fat LTO objects); the compiler is ${CMAKE_CXX_COMPILER_ID}")
  endif()
  add_compile_options(-flto=auto -ffat-lto-objects)
  add_link_options("$<IF:$<BOOL:$<TARGET_PROPERTY:HUBRT_LTO>>,-flto=auto,-fno-lto>")
endif()

# hubrt_linked_targets(<target> <out>): what <target> links, directly (its LINK_LIBRARIES, for a
# target that is not an interface library) and through its interface (INTERFACE_LINK_LIBRARIES).
function(hubrt_linked_targets target out)
  set(links "")
  get_target_property(type ${target} TYPE)
  if(NOT type STREQUAL "INTERFACE_LIBRARY")
    get_target_property(direct ${target} LINK_LIBRARIES)
    if(direct)
      list(APPEND links ${direct})
    endif()
  endif()
  get_target_property(interface ${target} INTERFACE_LINK_LIBRARIES)
  if(interface)
    list(APPEND links ${interface})
  endif()
  set(${out} ${links} PARENT_SCOPE)
endfunction()

# hubrt_target_defaults(<target>): warnings (errors when HUBRT_WERROR) for our own code only.
function(hubrt_target_defaults target)
  get_target_property(_type ${target} TYPE)
  if(_type STREQUAL "INTERFACE_LIBRARY")
    return()
  endif()
  target_compile_options(${target} PRIVATE
    $<$<COMPILE_LANGUAGE:CXX>:${HUBRT_WARNINGS}>
    $<$<COMPILE_LANGUAGE:C>:${HUBRT_C_WARNINGS}>
    $<$<BOOL:${HUBRT_WERROR}>:-Werror>)
  # HUBRT_UNITY_LIBRARIES (the sanitizer, fuzz and cross presets): a library's files compiled as
  # unity sources of up to 8, as HUBRT_UNITY_TESTS does for the test programs, and for the same
  # reason: the precompiled header saves parsing, not instantiating and generating the same
  # templates in every file (docs/ci.md, "Libraries as unity sources"). Not the PCH's host (CMake
  # cannot then resolve the header the libraries reuse). The cross builds, which the board
  # packages come from, too: what that did to the board programs' sizes is in docs/board-size.md.
  # host-release and host-debug compile file by file.
  if(HUBRT_UNITY_LIBRARIES AND _type MATCHES "^(STATIC|SHARED|OBJECT|MODULE)_LIBRARY$"
     AND NOT target STREQUAL "hubrt_library_pch")
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON)
  endif()
  # GCC's -Wsubobject-linkage is for a class defined in a header whose member's type is in an
  # anonymous namespace (each file including it would define a different class). A unity source
  # includes the .cc files, so GCC takes a class defined in one for a header's (the cross build:
  # LiftDriveServer::Session in hal/fake/modbus). host-debug compiles file by file with GCC and
  # keeps the warning for real headers.
  get_target_property(_unity ${target} UNITY_BUILD)
  if(_unity AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE $<$<COMPILE_LANGUAGE:CXX>:-Wno-subobject-linkage>)
  endif()
endfunction()

# HUBRT_SHARED_LIBS (top-level CMakeLists.txt): hubrt's own libraries as shared objects in the
# test builds. Statically linked, every one of ~130 sanitizer test programs carried its own copy of
# the libraries it uses (hubd alone 234 MB with ASan+UBSan: their instrumentation data and its
# relocations), 4.5 GB of programs and 0.85 GB of archives in a 6.8 GB build, and most of the build's
# time was spent linking them. Shared, each library is built and linked once. Everything that
# ships (release, cross, board packages) stays static.
if(HUBRT_SHARED_LIBS)
  set(HUBRT_LIBRARY_KIND SHARED)
  # The composition root (libhubrt_assembly) calls hub_types(), which the program defines (its
  # hub-type registry, hubs/HubTypes.cmake). A static link takes only the objects a test uses, so a
  # test of the twin rules needed no registry; a shared library is linked whole, so programs are
  # let link with such a reference left open (it would fail when called, as the static link did
  # at once). The static builds still check every reference at link time.
  add_link_options("$<$<STREQUAL:$<TARGET_PROPERTY:TYPE>,EXECUTABLE>:LINKER:--allow-shlib-undefined>")
else()
  set(HUBRT_LIBRARY_KIND STATIC)
endif()

# hubrt_add_library(<name> [INTERFACE] SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Static, or shared with HUBRT_SHARED_LIBS. Headers live in <folder>/include.
function(hubrt_add_library name)
  cmake_parse_arguments(A "INTERFACE" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  if(A_INTERFACE)
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${CMAKE_CURRENT_SOURCE_DIR}/include)
    target_link_libraries(${name} INTERFACE ${A_PUBLIC_DEPS})
    return()
  endif()
  add_library(${name} ${HUBRT_LIBRARY_KIND} ${A_SOURCES})
  target_include_directories(${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(${name} PUBLIC ${A_PUBLIC_DEPS} PRIVATE ${A_PRIVATE_DEPS})
  hubrt_target_defaults(${name})
  _hubrt_library_pch(${name} "${A_SOURCES}")
endfunction()

# HUBRT_PCH: hubrt's own libraries reuse one precompiled header of the third-party headers most of
# them include (the standard library, fmt, spdlog), built by the library hubrt_library_pch, a
# library of the same kind as theirs (shared in the sanitizer builds, static in the cross build: GCC
# refuses a header made with the shared library's <target>_EXPORTS macro where it is not defined);
# the test programs have their own, hubrt_test_pch below. fmt and spdlog are precompiled in the mode
# they are linked in (Debian's shared libfmt; Debian's libspdlog.so or, static, hubrt_spdlog's
# compiled spdlog: base/spdlog), so each library gets those definitions. Both headers end with
# hubrt/fmt/vformat_once.h, so their users link fmt's engine compiled once (hubrt_fmt_vformat). C
# sources (Cyclone's instance map, IDL types) are compiled without it.
get_filename_component(HUBRT_FMT_VFORMAT_ONCE_HEADER
  "${CMAKE_CURRENT_LIST_DIR}/../../base/fmt/include/hubrt/fmt/vformat_once.h" ABSOLUTE)
function(_hubrt_library_pch name sources)
  if(NOT HUBRT_PCH)
    return()
  endif()
  foreach(source IN LISTS sources)
    if(source MATCHES "\\.c$")
      # Nor in a unity source: CMake's C unity file would want a C header from the PCH's host.
      set_source_files_properties(${source} TARGET_DIRECTORY ${name} PROPERTIES SKIP_PRECOMPILE_HEADERS ON
                                  SKIP_UNITY_BUILD_INCLUSION ON)
    endif()
  endforeach()
  set(_definitions FMT_SHARED)
  if(HUBRT_SHARED_LIBS)
    list(APPEND _definitions SPDLOG_SHARED_LIB)
  endif()
  list(APPEND _definitions SPDLOG_COMPILED_LIB SPDLOG_FMT_EXTERNAL)
  if(NOT TARGET hubrt_library_pch)
    set(_src ${CMAKE_BINARY_DIR}/hubrt_library_pch.cc)
    file(WRITE ${_src} "// The host of the libraries' precompiled header (HUBRT_PCH).\n")
    add_library(hubrt_library_pch ${HUBRT_LIBRARY_KIND} ${_src})
    target_compile_definitions(hubrt_library_pch PRIVATE ${_definitions})
    hubrt_target_pch(hubrt_library_pch
      <algorithm> <array> <atomic> <chrono> <cstdint> <functional> <map> <memory> <mutex> <optional> <span>
      <string> <string_view> <thread> <unordered_map> <variant> <vector>
      <fmt/format.h> <spdlog/spdlog.h>)
    hubrt_target_defaults(hubrt_library_pch)
  endif()
  target_compile_definitions(${name} PRIVATE ${_definitions})
  target_link_libraries(${name} PRIVATE hubrt_fmt_vformat)
  target_precompile_headers(${name} REUSE_FROM hubrt_library_pch)
endfunction()

# hubrt_target_pch(<target> <header>...): under HUBRT_PCH, a precompiled header of the target's own,
# of the given headers and hubrt/fmt/vformat_once.h: the libraries' host (hubrt_library_pch), and a
# library of another kind than the libraries' (hubctl's, static, in the shared builds). hubctl's library
# (56 files): 20 of them compiled 83.1 CPU-s without one, 65.0 with the standard library and fmt,
# 65.7 with nlohmann-json, CLI11 and yaml-cpp too, which fewer than half include (2026-11-29).
function(hubrt_target_pch target)
  if(NOT HUBRT_PCH)
    return()
  endif()
  target_precompile_headers(${target} PRIVATE ${ARGN} ${HUBRT_FMT_VFORMAT_ONCE_HEADER})
  target_link_libraries(${target} PRIVATE hubrt_fmt_vformat)
  target_compile_options(${target} PRIVATE $<$<CXX_COMPILER_ID:Clang>:-Xclang -fno-pch-timestamp>)
endfunction()

# hubrt_add_test(<name> SOURCES ... [LIBS ...] [LABELS ...] [TIMEOUT s])
# One gtest binary; each TEST() becomes its own CTest entry (listed at test time, so that
# cross builds list them through the emulator only when tests run). LABELS: unit (default),
# integration, conformance, threaded (also run under TSan), slow (not in the default suite).
# A module a program loads with dlopen (hal/common/module_loader.h), e.g. the HTTP client, so that
# only a hub that needs it maps its libraries. It exports its entry point only: the copies of the
# libraries linked into it stay its own.
#   hubrt_add_module(<target> OUTPUT_NAME <file name without .so> SOURCES ... LIBS ...)
function(hubrt_add_module target)
  cmake_parse_arguments(ARG "" "OUTPUT_NAME" "SOURCES;LIBS" ${ARGN})
  add_library(${target} MODULE ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE ${ARG_LIBS})
  set_target_properties(${target} PROPERTIES PREFIX "" OUTPUT_NAME ${ARG_OUTPUT_NAME}
    CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
  target_link_options(${target} PRIVATE -Wl,--exclude-libs,ALL)
  hubrt_target_defaults(${target})
endfunction()

# The library that loads `module`: whatever links it gets the module built too. In a native build
# it is also told the module's file in the build tree (the macro `define`), so programs and tests
# run from the build tree find it; a cross build's programs find it only where a package installs it.
function(hubrt_module_loader loader module define)
  if(CMAKE_CROSSCOMPILING)
    target_compile_definitions(${loader} PRIVATE ${define}="")
  else()
    target_compile_definitions(${loader} PRIVATE ${define}="$<TARGET_FILE:${module}>")
  endif()
  add_dependencies(${loader} ${module})
endfunction()

# HUBRT_PCH (the sanitizer presets): every test program reuses one precompiled header of the
# heavy third-party headers they share (GoogleTest, GoogleMock, spdlog, fmt, nlohmann-json and the
# standard library), built once by the program hubrt_test_pch. At -O0 with ASan a test object spends
# about a quarter of its compile reading those headers (clang -ftime-trace, 2026-11-29), which a
# precompiled header does once. clang accepts a precompiled header only where every macro it was
# built with is defined alike on the command line, so each test links what the header was built
# with (hubrt_test_pch_deps) and gets the same definitions; macros of a test's own are allowed.
# It ends with hubrt/fmt/vformat_once.h, as the libraries' header does.
# The cross builds use both headers too (GCC: 0.65x the CPU of a test object, 0.59x of a library's,
# samples of 16 and 22, 2026-11-29: docs/ci.md); the release build compiles every file on its own.
function(_hubrt_test_pch)
  if(TARGET hubrt_test_pch)
    return()
  endif()
  add_library(hubrt_test_pch_deps INTERFACE)
  target_link_libraries(hubrt_test_pch_deps INTERFACE GTest::gtest GTest::gmock hubrt_spdlog fmt::fmt
                        nlohmann_json::nlohmann_json hubrt_fmt_vformat)
  set(_src ${CMAKE_BINARY_DIR}/hubrt_test_pch_main.cc)
  file(WRITE ${_src} "int main() { return 0; }\n")
  add_executable(hubrt_test_pch ${_src})
  target_link_libraries(hubrt_test_pch PRIVATE hubrt_test_pch_deps)
  target_precompile_headers(hubrt_test_pch PRIVATE
    <algorithm> <chrono> <functional> <map> <memory> <optional> <string> <string_view> <thread> <vector>
    <gtest/gtest.h> <gmock/gmock.h> <fmt/format.h> <spdlog/spdlog.h> ${HUBRT_FMT_VFORMAT_ONCE_HEADER})
  target_compile_options(hubrt_test_pch PRIVATE $<$<CXX_COMPILER_ID:Clang>:-Xclang -fno-pch-timestamp>
                         ${_hubrt_test_san_flags})
  hubrt_target_defaults(hubrt_test_pch)
endfunction()

function(hubrt_add_test name)
  if(NOT HUBRT_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(A "PROCESS_PER_TEST" "TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  if(NOT A_LABELS)
    set(A_LABELS unit)
  endif()
  if(NOT A_TIMEOUT)
    set(A_TIMEOUT 120)
  endif()
  # HUBRT_TEST_LABELS (a list; empty: all) builds only the tests with one of those labels: CI's
  # cross tier (toolchain/cross-test --labels) leaves out what the host build runs already.
  if(HUBRT_TEST_LABELS)
    set(_selected FALSE)
    foreach(_label IN LISTS A_LABELS)
      if(_label IN_LIST HUBRT_TEST_LABELS)
        set(_selected TRUE)
      endif()
    endforeach()
    if(NOT _selected)
      return()
    endif()
  endif()
  # The kernel tier boots an x86-64 guest that runs host binaries (tests/kernel, which adds
  # nothing in a cross build): a cross build has nothing to run kernel tests on.
  if(CMAKE_CROSSCOMPILING AND "kernel" IN_LIST A_LABELS)
    return()
  endif()
  add_executable(${name} ${A_SOURCES})
  # HUBRT_UNITY_TESTS (CI's presets: host-asan, host-tsan, the cross builds): the program's files
  # compiled as unity sources of up to 8 (CMake's UNITY_BUILD_BATCH_SIZE). The precompiled header
  # saves each file parsing GoogleTest and the standard library, not instantiating and generating
  # the same templates (GoogleTest's, the messages', hubrt's) again: the ASan build's 407 test
  # objects took 538 CPU-s, its 146 unity objects 335, the whole build 0.82x the time (docs/ci.md,
  # "Test programs as unity sources").
  # So file-scope names must differ across a program's files (the compiler names a clash), and a
  # change to one file recompiles its batch. host-debug, which `make lint` uses, keeps a
  # compilation database entry per file for clang-tidy and editors.
  if(HUBRT_UNITY_TESTS)
    set_target_properties(${name} PROPERTIES UNITY_BUILD ON)
  endif()
  target_link_libraries(${name} PRIVATE ${A_LIBS} GTest::gtest GTest::gmock GTest::gtest_main)
  if(HUBRT_PCH)
    _hubrt_test_pch()
    target_link_libraries(${name} PRIVATE hubrt_test_pch_deps)
    target_precompile_headers(${name} REUSE_FROM hubrt_test_pch)
  endif()
  # The ThreadSanitizer build runs only these: target `threaded-tests` (top-level CMakeLists.txt).
  if("threaded" IN_LIST A_LABELS)
    set_property(GLOBAL APPEND PROPERTY HUBRT_THREADED_TEST_TARGETS ${name})
  endif()
  hubrt_target_defaults(${name})
  target_compile_options(${name} PRIVATE ${_hubrt_test_san_flags})
  # HUBRT_TEST_ENVIRONMENT (a list of NAME=value, set by the project: tests/new_hub) goes into every
  # test's environment.
  set(_env ${HUBRT_TEST_ENVIRONMENT})
  if(CMAKE_CROSSCOMPILING_EMULATOR)
    # Under qemu-user (no binfmt_misc) a test cannot exec a target program directly: tests that
    # start programs put this space-separated command in front of them.
    list(JOIN CMAKE_CROSSCOMPILING_EMULATOR " " _emulator)
    list(APPEND _env "HUBRT_TARGET_EMULATOR=${_emulator}")
  endif()
  # A unit or threaded test program (no integration, conformance, kernel or slow label) is one CTest
  # test: all its tests in one process. Starting a process per test cost 0.12-0.17 CPU-s each under
  # ASan, 35-50 times a unit test itself: the 1363 tests of 91 programs whose every test took under
  # 2.5 s took 341 CPU-s one process each and 73 a process per program (docs/ci.md, 2026-11-30).
  # GoogleTest's brief output keeps only what failed.
  # Programs whose tests start hubd, hubctl or a station keep a CTest test per test: those are the
  # slow ones, scheduled longest first across the cores. PROCESS_PER_TEST keeps that for a program
  # whose tests need a process each (one process-wide Cyclone log sink, the environment).
  set(_whole TRUE)
  foreach(_label IN LISTS A_LABELS)
    if(NOT _label MATCHES "^(unit|threaded)$")
      set(_whole FALSE)
    endif()
  endforeach()
  if(A_PROCESS_PER_TEST)
    set(_whole FALSE)
  endif()
  if(_whole)
    add_test(NAME ${name} COMMAND ${name} --gtest_brief=1)
    # The program's tests together, under TSan or qemu-user 5-10 times slower than here.
    math(EXPR _whole_timeout "${A_TIMEOUT} * 3")
    set_tests_properties(${name} PROPERTIES LABELS "${A_LABELS}" TIMEOUT ${_whole_timeout})
    if(_env)
      set_tests_properties(${name} PROPERTIES ENVIRONMENT "${_env}")
    endif()
    return()
  endif()
  # Labels and timeout are applied by a small script included after the discovered tests:
  # gtest_discover_tests' PROPERTIES loses the separators of a list value in PRE_TEST mode.
  gtest_discover_tests(${name}
    DISCOVERY_MODE PRE_TEST
    DISCOVERY_TIMEOUT 60
    TEST_LIST ${name}_TESTS)
  set(_cross_env "")
  if(_env)
    list(JOIN _env ";" _env_text)
    set(_cross_env " ENVIRONMENT \"${_env_text}\"")
  endif()
  set(_props ${CMAKE_CURRENT_BINARY_DIR}/${name}_properties.cmake)
  file(GENERATE OUTPUT ${_props} CONTENT
    "foreach(_t IN LISTS ${name}_TESTS)\n  set_tests_properties(\"\${_t}\" PROPERTIES LABELS \"${A_LABELS}\" TIMEOUT ${A_TIMEOUT}${_cross_env})\nendforeach()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${_props})
endfunction()
