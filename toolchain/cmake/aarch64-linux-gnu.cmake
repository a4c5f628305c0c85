# Cross toolchain: Debian bookworm amd64 host -> 64-bit Raspberry Pi OS / Debian arm64 (Pi 3, 4, 5).
# Prepare with toolchain/prepare-target arm64; used by the cross-arm64 preset.
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(HUBRT_TARGET_TRIPLET aarch64-linux-gnu)
set(HUBRT_TARGET_DEB_ARCH arm64)
set(HUBRT_TARGET_QEMU qemu-aarch64-static)
include(${CMAKE_CURRENT_LIST_DIR}/HubrtCrossToolchain.cmake)
