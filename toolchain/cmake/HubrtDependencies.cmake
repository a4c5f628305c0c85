# The libraries hubrt builds against, found the same way by the project itself and by a project
# that imports its build's targets (tests/new_hub: the targets name these imported ones).
find_package(CycloneDDS 0.10 REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(CLI11 REQUIRED)
find_package(fmt REQUIRED)
find_package(spdlog REQUIRED)
find_package(nlohmann_json REQUIRED)
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(GPIOD REQUIRED IMPORTED_TARGET libgpiod>=1.6)
pkg_check_modules(MODBUS REQUIRED IMPORTED_TARGET libmodbus>=3.1)
pkg_check_modules(SYSTEMD REQUIRED IMPORTED_TARGET libsystemd)
# Debian's cpp-httplib is a shared library built with OpenSSL, zlib and Brotli support: its
# pkg-config flags must be used, or the header's classes differ from the library's.
pkg_check_modules(HTTPLIB REQUIRED IMPORTED_TARGET cpp-httplib>=0.11)
pkg_check_modules(EVDEV REQUIRED IMPORTED_TARGET libevdev)  # RFID keyboard-wedge readers (hal/linux/rfid)
find_package(OpenSSL REQUIRED COMPONENTS Crypto)           # operator allow-list hashes (hubs/operator_hub)
# ROS 1 (hubbridge, firmware/ros1), where Debian's ROS 1 is installed.
pkg_check_modules(ROS1 QUIET IMPORTED_TARGET roscpp topic_tools)
