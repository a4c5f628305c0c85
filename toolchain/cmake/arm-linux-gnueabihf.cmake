# Cross toolchain: Debian bookworm amd64 host -> 32-bit Raspberry Pi OS / Debian armhf.
# Debian armhf is ARMv7 hard-float: Pi 2, 3, 4, 5 — not Pi Zero / Pi 1 (ARMv6).
# Prepare with toolchain/prepare-target armhf; used by the cross-armhf preset.
set(CMAKE_SYSTEM_PROCESSOR armv7l)
set(HUBRT_TARGET_TRIPLET arm-linux-gnueabihf)
set(HUBRT_TARGET_DEB_ARCH armhf)
set(HUBRT_TARGET_QEMU qemu-arm-static)
include(${CMAKE_CURRENT_LIST_DIR}/HubrtCrossToolchain.cmake)
