# Cross toolchain: Debian bookworm amd64 host -> 64-bit Raspberry Pi OS / Debian arm64 (Pi 3, 4, 5).
# Prepare with toolchain/prepare-target arm64; used by the cross-arm64 preset.
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(HUBRT_TARGET_TRIPLET aarch64-linux-gnu)
set(HUBRT_TARGET_DEB_ARCH arm64)
set(HUBRT_TARGET_QEMU qemu-aarch64-static)
# The largest page of a Raspberry Pi kernel: the Pi 5's own (kernel_2712) uses 16 KiB pages, the
# others 4 KiB; none 64 KiB, which GNU ld assumes for arm64 by default. To that default it aligned
# the end of the data made read-only after relocation by padding the file: up to 64 KiB more per
# program (docs/board-size.md). Programs aligned to 16 KiB run on 4 KiB and 16 KiB kernels alike.
# (armhf's linker lays the same data out without padding the file: its default is kept.) Used by
# the top-level CMakeLists.txt.
set(HUBRT_TARGET_MAX_PAGE_SIZE 16384)
include(${CMAKE_CURRENT_LIST_DIR}/HubrtCrossToolchain.cmake)
