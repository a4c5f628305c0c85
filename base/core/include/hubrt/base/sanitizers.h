#pragma once

// Which sanitizer this translation unit is built with, the same under both compilers: GCC defines
// __SANITIZE_ADDRESS__ / __SANITIZE_THREAD__, clang answers __has_feature (the ASan+UBSan build is
// clang's, the TSan build GCC's: CMakePresets.json). UBSan has no such macro in either compiler:
// the build defines HUBRT_SANITIZE_UNDEFINED (toolchain/cmake/HubrtTargets.cmake).
#if defined(__SANITIZE_ADDRESS__)
#define HUBRT_SANITIZE_ADDRESS 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HUBRT_SANITIZE_ADDRESS 1
#endif
#endif

#if defined(__SANITIZE_THREAD__)
#define HUBRT_SANITIZE_THREAD 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define HUBRT_SANITIZE_THREAD 1
#endif
#endif
