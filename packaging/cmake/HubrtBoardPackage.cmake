# One board's Debian package (CPack, DEB generator), made by toolchain/package-board:
#   cmake --preset cross-arm64 -DHUBRT_PACKAGE_BOARD=rpi4-tool-ecu -DHUBRT_BOARD_INFO=<host hubrt-board-info>
#   cmake --build build/cross-arm64 --target hubrt-deb      # -> build/cross-arm64/packages/*.deb
# Included by the top-level CMakeLists.txt only when HUBRT_PACKAGE_BOARD is set, so other builds
# neither read boards here nor generate CPack files.
#
# The package holds installed files only (component hubrt-board: `cmake --install` drops the build
# RPATH into the sysroot), stripped. Depends is derived at packaging time by dpkg-shlibdeps from
# the staged binaries, with the symbols/shlibs files prepare-target collects in <sysroot>/DEBIAN
# (DebDepends.cmake).

if(NOT CMAKE_CROSSCOMPILING OR NOT HUBRT_TARGET_DEB_ARCH OR NOT HUBRT_SYSROOT)
  message(FATAL_ERROR "HUBRT_PACKAGE_BOARD needs a cross build (preset cross-arm64 or cross-armhf): "
                      "board packages are for Raspberry Pi targets")
endif()
if(NOT HUBRT_BOARD_INFO)
  message(FATAL_ERROR "HUBRT_PACKAGE_BOARD needs -DHUBRT_BOARD_INFO=<hubrt-board-info built for this machine> "
                      "(toolchain/package-board builds and passes it)")
endif()

set(_pkg_board_file "${PROJECT_SOURCE_DIR}/boards/${HUBRT_PACKAGE_BOARD}.yaml")
if(NOT EXISTS "${_pkg_board_file}")
  message(FATAL_ERROR "HUBRT_PACKAGE_BOARD=${HUBRT_PACKAGE_BOARD}: no board file ${_pkg_board_file}")
endif()
execute_process(
  COMMAND "${HUBRT_BOARD_INFO}" package "${_pkg_board_file}" --hubs-dir "${PROJECT_SOURCE_DIR}/hubs"
  OUTPUT_VARIABLE _pkg_facts ERROR_VARIABLE _pkg_error RESULT_VARIABLE _pkg_result)
if(NOT _pkg_result EQUAL 0)
  message(FATAL_ERROR "cannot package board ${HUBRT_PACKAGE_BOARD}:\n${_pkg_error}")
endif()

macro(_hubrt_pkg_fact var)
  string(JSON ${var} GET "${_pkg_facts}" ${ARGN})
endmacro()
_hubrt_pkg_fact(HUBRT_PKG_BOARD board)
_hubrt_pkg_fact(HUBRT_PKG_DESCRIPTION description)
_hubrt_pkg_fact(HUBRT_PKG_ARCH arch)
_hubrt_pkg_fact(HUBRT_PKG_HUB hub)
_hubrt_pkg_fact(HUBRT_PKG_RATE_HZ rate_hz)
_hubrt_pkg_fact(HUBRT_PKG_WATCHDOG_SEC watchdog_sec)
_hubrt_pkg_fact(_pkg_gpio gpio)
_hubrt_pkg_fact(_pkg_http http)
string(JSON _pkg_can_count LENGTH "${_pkg_facts}" can)
string(JSON _pkg_serial_count LENGTH "${_pkg_facts}" serial_devices)
string(JSON _pkg_input_count LENGTH "${_pkg_facts}" input_devices)

if(NOT HUBRT_PKG_BOARD STREQUAL HUBRT_PACKAGE_BOARD)
  message(FATAL_ERROR "${_pkg_board_file} names board '${HUBRT_PKG_BOARD}': hubd finds boards by file "
                      "name, so the file must be ${HUBRT_PKG_BOARD}.yaml")
endif()
if(NOT HUBRT_PKG_ARCH STREQUAL HUBRT_TARGET_DEB_ARCH)
  message(FATAL_ERROR "board ${HUBRT_PKG_BOARD} is for ${HUBRT_PKG_ARCH}; this build is for "
                      "${HUBRT_TARGET_DEB_ARCH} (use the preset cross-${HUBRT_PKG_ARCH})")
endif()
set(_pkg_hub_dir "${PROJECT_SOURCE_DIR}/hubs/${HUBRT_PKG_HUB}")
# A changed board or hub file re-runs this configure, so the package never lags behind them.
set_property(DIRECTORY "${PROJECT_SOURCE_DIR}" APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
             "${_pkg_board_file}" "${_pkg_hub_dir}/${HUBRT_PKG_HUB}.yaml")

# --- what the board needs: groups, CAN interfaces ----------------------------------------------
set(_pkg_groups "")
set(HUBRT_PKG_SYSUSERS_GROUPS "")
if(_pkg_gpio)
  list(APPEND _pkg_groups gpio)
  string(APPEND HUBRT_PKG_SYSUSERS_GROUPS "g gpio -\nm hubrt gpio\n")
endif()
if(_pkg_serial_count GREATER 0)
  list(APPEND _pkg_groups dialout)  # Modbus RTU, serial RFID readers (/dev/ttyUSB*, /dev/ttyAMA*)
  string(APPEND HUBRT_PKG_SYSUSERS_GROUPS "m hubrt dialout\n")
endif()
if(_pkg_input_count GREATER 0)
  list(APPEND _pkg_groups input)  # RFID keyboard-wedge readers (/dev/input/event*)
  string(APPEND HUBRT_PKG_SYSUSERS_GROUPS "m hubrt input\n")
endif()
string(STRIP "${HUBRT_PKG_SYSUSERS_GROUPS}" HUBRT_PKG_SYSUSERS_GROUPS)
if(_pkg_groups)
  list(JOIN _pkg_groups " " _pkg_groups_text)
  set(HUBRT_PKG_GROUPS_LINE "SupplementaryGroups=${_pkg_groups_text}")
else()
  set(HUBRT_PKG_GROUPS_LINE "# No device groups: the board uses no GPIO and no serial line.")
endif()

set(_pkg_gen "${CMAKE_BINARY_DIR}/packaging/${HUBRT_PKG_BOARD}")
file(REMOVE_RECURSE "${_pkg_gen}")  # a board switched in this build leaves no files of the old one
set(_pkg_templates "${CMAKE_CURRENT_LIST_DIR}/../deb")
set(_pkg_networks "")
set(HUBRT_PKG_NETWORKD "")
set(HUBRT_PKG_AF_CAN "")
set(HUBRT_PKG_POSTINST_NETWORKD "")
set(HUBRT_PKG_POSTRM_NETWORKD "")
if(_pkg_can_count GREATER 0)
  set(HUBRT_PKG_NETWORKD " systemd-networkd.service")
  set(HUBRT_PKG_AF_CAN " AF_CAN")
  set(HUBRT_PKG_POSTINST_NETWORKD
      "    # New .network files and networkd.conf: a running systemd-networkd restarts (it only\n"
      "    # manages the CAN interfaces); else the hubd unit starts it.\n"
      "    systemctl try-restart systemd-networkd.service || true")
  set(HUBRT_PKG_POSTRM_NETWORKD
      "      if systemctl is-active --quiet systemd-networkd.service; then networkctl reload || true; fi")
  string(JOIN "" HUBRT_PKG_POSTINST_NETWORKD ${HUBRT_PKG_POSTINST_NETWORKD})
  math(EXPR _pkg_last "${_pkg_can_count} - 1")
  foreach(i RANGE ${_pkg_last})
    _hubrt_pkg_fact(HUBRT_PKG_CAN_BUS can ${i} bus)
    _hubrt_pkg_fact(HUBRT_PKG_CAN_INTERFACE can ${i} interface)
    _hubrt_pkg_fact(HUBRT_PKG_CAN_BITRATE can ${i} bitrate)
    set(_pkg_network "${_pkg_gen}/80-hubrt-${HUBRT_PKG_CAN_INTERFACE}.network")
    configure_file("${_pkg_templates}/can.network.in" "${_pkg_network}" @ONLY)
    list(APPEND _pkg_networks "${_pkg_network}")
  endforeach()
endif()

configure_file("${_pkg_templates}/hubd.service.in" "${_pkg_gen}/hubd.service" @ONLY)
configure_file("${_pkg_templates}/hubrt-sysusers.conf.in" "${_pkg_gen}/hubrt.conf" @ONLY)
foreach(script postinst prerm postrm)
  configure_file("${_pkg_templates}/${script}.in" "${_pkg_gen}/control/${script}" @ONLY
                 FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE WORLD_READ
                                  WORLD_EXECUTE)
endforeach()

# --- contents: everything in component hubrt-board, paths relative to / ------------------------
set(_pkg_component COMPONENT hubrt-board EXCLUDE_FROM_ALL)
# The board build of hubd with the board's hub type alone (firmware/hubd: hubd_board_<hub>; no fake
# backend, no simulators, no other hub type), installed as hubd.
if(NOT TARGET hubd_board_${HUBRT_PKG_HUB})
  message(FATAL_ERROR "board ${HUBRT_PKG_BOARD} runs hub '${HUBRT_PKG_HUB}': no board program "
                      "hubd_board_${HUBRT_PKG_HUB} (a board package carries one hub type, one of hubs/)")
endif()
install(TARGETS hubd_board_${HUBRT_PKG_HUB} hubctl RUNTIME DESTINATION usr/bin ${_pkg_component})
# The HTTP client module (hal/linux/http: cpp-httplib and, through Debian's build of it, OpenSSL),
# only for a board with REST devices; hubd loads it from ../lib/hubrt next to /usr/bin.
set(_pkg_binaries usr/bin/hubd usr/bin/hubctl)
set(_pkg_programs hubd_board_${HUBRT_PKG_HUB} hubctl)
if(_pkg_http)
  install(TARGETS hubrt_http_module LIBRARY DESTINATION usr/lib/hubrt ${_pkg_component})
  list(APPEND _pkg_binaries usr/lib/hubrt/hubrt-http.so)
  list(APPEND _pkg_programs hubrt_http_module)
endif()
if(HUBRT_PKG_HUB STREQUAL "operator_hub")
  install(TARGETS operator-enrol RUNTIME DESTINATION usr/bin ${_pkg_component})  # the allow-list's writer
endif()
install(FILES "${_pkg_board_file}" DESTINATION etc/hubrt/boards ${_pkg_component})
set(_pkg_conffiles "/etc/hubrt/boards/${HUBRT_PKG_BOARD}.yaml" "/etc/default/hubd")
# The hub's configuration, and its conformance profile where it has one (hubctl conformance on
# the Pi finds it there).
# operators.list: the operator hub's allow-list (a conffile: enrolled operators survive upgrades).
foreach(file ${HUBRT_PKG_HUB}.yaml conformance.yaml operators.list)
  if(EXISTS "${_pkg_hub_dir}/${file}")
    install(FILES "${_pkg_hub_dir}/${file}" DESTINATION etc/hubrt/hubs/${HUBRT_PKG_HUB} ${_pkg_component})
    list(APPEND _pkg_conffiles "/etc/hubrt/hubs/${HUBRT_PKG_HUB}/${file}")
  endif()
endforeach()
install(FILES "${_pkg_templates}/hubd.default" DESTINATION etc/default RENAME hubd ${_pkg_component})
install(FILES "${_pkg_gen}/hubd.service" DESTINATION lib/systemd/system ${_pkg_component})
install(FILES "${_pkg_gen}/hubrt.conf" DESTINATION usr/lib/sysusers.d ${_pkg_component})
if(_pkg_gpio)
  install(FILES "${_pkg_templates}/60-hubrt-gpio.rules" DESTINATION lib/udev/rules.d ${_pkg_component})
endif()
if(_pkg_networks)
  install(FILES ${_pkg_networks} DESTINATION lib/systemd/network ${_pkg_component})
  install(FILES "${_pkg_templates}/networkd-hubrt.conf" DESTINATION lib/systemd/networkd.conf.d
          RENAME hubrt.conf ${_pkg_component})
endif()
list(JOIN _pkg_conffiles "\n" _pkg_conffiles_text)
file(WRITE "${_pkg_gen}/control/conffiles" "${_pkg_conffiles_text}\n")

# --- CPack ---------------------------------------------------------------------------------------
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME "hubrt-${HUBRT_PKG_BOARD}")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE "${HUBRT_TARGET_DEB_ARCH}")
set(HUBRT_PACKAGE_MAINTAINER "hubrt maintainers <hubrt@localhost>" CACHE STRING
    "Maintainer field of the board packages")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${HUBRT_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "hubrt hub ${HUBRT_PKG_HUB} for board ${HUBRT_PKG_BOARD}")
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
    "hubrt hub ${HUBRT_PKG_HUB} for board ${HUBRT_PKG_BOARD}\n"
    "${HUBRT_PKG_DESCRIPTION}. hubd runs as the systemd service hubd (user hubrt) with the board\n"
    "file and the hub configuration under /etc/hubrt. hubctl lists, watches, commands and checks\n"
    "hubs over DDS.")
string(JOIN "" CPACK_DEBIAN_PACKAGE_DESCRIPTION ${CPACK_DEBIAN_PACKAGE_DESCRIPTION})
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# One board package per Pi: installing another replaces the first (same /usr/bin/hubd, same unit).
set(CPACK_DEBIAN_PACKAGE_PROVIDES hubrt-board)
set(CPACK_DEBIAN_PACKAGE_CONFLICTS hubrt-board)
set(CPACK_DEBIAN_PACKAGE_REPLACES hubrt-board)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA "${_pkg_gen}/control/postinst" "${_pkg_gen}/control/prerm"
                                       "${_pkg_gen}/control/postrm" "${_pkg_gen}/control/conffiles")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)
# Only component hubrt-board, installed under / (destinations above are relative to it).
set(CPACK_INSTALL_CMAKE_PROJECTS "${CMAKE_BINARY_DIR};hubrt;hubrt-board;/")
set(CPACK_PACKAGING_INSTALL_PREFIX "/")
set(CPACK_STRIP_FILES TRUE)
set(CPACK_PACKAGE_DIRECTORY "${CMAKE_BINARY_DIR}/packages")
# Depends: dpkg-shlibdeps on the staged binaries, after CPack installed them and before it packs.
# systemd: systemd-sysusers in postinst, systemd-networkd for CAN.
set(CPACK_PRE_BUILD_SCRIPTS "${CMAKE_CURRENT_LIST_DIR}/DebDepends.cmake")
set(HUBRT_PKG_DEB_DEPENDS_EXTRA "systemd")
set(CPACK_PROJECT_CONFIG_FILE "${_pkg_gen}/cpack-settings.cmake")
file(WRITE "${CPACK_PROJECT_CONFIG_FILE}"
     "# Read by cpack (packaging/cmake/HubrtBoardPackage.cmake): what DebDepends.cmake needs.\n"
     "set(HUBRT_PKG_SYSROOT [==[${HUBRT_SYSROOT}]==])\n"
     "set(HUBRT_PKG_DEB_ARCH [==[${HUBRT_TARGET_DEB_ARCH}]==])\n"
     "set(HUBRT_PKG_DEB_DEPENDS_EXTRA [==[${HUBRT_PKG_DEB_DEPENDS_EXTRA}]==])\n"
     "set(HUBRT_PKG_BINARIES ${_pkg_binaries})\n")
include(CPack)

# cmake --build <dir> --target hubrt-deb: builds hubd (the board program of its hub type,
# hubd_board_<hub>), hubctl and, for a board with REST devices, the HTTP client module (nothing
# else) and packs them.
add_custom_target(hubrt-deb
  COMMAND "${CMAKE_CPACK_COMMAND}" --config "${CMAKE_BINARY_DIR}/CPackConfig.cmake"
  DEPENDS ${_pkg_programs}
  WORKING_DIRECTORY "${CMAKE_BINARY_DIR}"
  COMMENT "Packing hubrt-${HUBRT_PKG_BOARD} (${HUBRT_TARGET_DEB_ARCH})"
  VERBATIM)
message(STATUS "Board package: hubrt-${HUBRT_PKG_BOARD} (${HUBRT_TARGET_DEB_ARCH}), target hubrt-deb")

# ctest -L cross in this build: make the package, then check it as a Pi would meet it.
if(HUBRT_BUILD_TESTS)
  find_package(Python3 REQUIRED COMPONENTS Interpreter)
  set(_pkg_deb "${CPACK_PACKAGE_DIRECTORY}/${CPACK_PACKAGE_NAME}_${CPACK_PACKAGE_VERSION}-${CPACK_DEBIAN_PACKAGE_RELEASE}_${HUBRT_TARGET_DEB_ARCH}.deb")
  add_test(NAME hubrt_board_package_build
           COMMAND "${CMAKE_COMMAND}" --build "${CMAKE_BINARY_DIR}" --target hubrt-deb)
  set_tests_properties(hubrt_board_package_build PROPERTIES
    FIXTURES_SETUP hubrt_board_package LABELS cross TIMEOUT 1800)
  add_test(NAME hubrt_board_package_check
           COMMAND "${Python3_EXECUTABLE}" "${PROJECT_SOURCE_DIR}/toolchain/check-package" "${_pkg_deb}"
                   --board "${HUBRT_PKG_BOARD}" --board-info "${HUBRT_BOARD_INFO}" --sysroot "${HUBRT_SYSROOT}")
  set_tests_properties(hubrt_board_package_check PROPERTIES
    FIXTURES_REQUIRED hubrt_board_package LABELS cross TIMEOUT 120)
endif()
