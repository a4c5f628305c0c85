// ThreadSanitizer suppressions for races it reports *inside* Cyclone DDS.
//
// Debian's libddsc is not built with ThreadSanitizer: its lock-free parts (atomics, the garbage
// collector's thread-time handshakes) are invisible to it, so TSan reports races between two
// Cyclone threads whenever Cyclone's own accesses pass through an intercepted function (free,
// malloc, memcpy, sendmsg, recvmsg, pthread mutexes). Measured here: 40 such reports in 30 test
// runs, every one with Cyclone code directly below the intercepted call on both sides.
//
// Suppressed by the top frame only, so that races in our code stay visible: in particular a
// callback running on a Cyclone thread while we free its state is reported (the free is an
// `operator delete`, the access is ours), which the broader alternatives do not do:
// `called_from_lib:libddsc` hides Cyclone's mutexes and thus invents races in our callbacks;
// `ignore_noninstrumented_modules=1` and `race:libddsc` hide a use-after-free in a callback.
// The price: a race whose first frame is one of these functions (or any function whose name
// contains one of these words) is not reported even when our code made the call; ASan still
// catches the use-after-free variants.
//
// Debian's cpp-httplib (libcpp-httplib.so, the MiR client and simulator, hubctl serve) is not
// built with ThreadSanitizer either, and shows the same class of report between two of its own
// server threads: an `operator new` in one and a `memcmp` in another, with only cpp-httplib below
// both (seen once in 3 TSan runs of hubrt_hal_mir_http_test; our code is in neither stack). Hence
// `memcmp`, with the same price as above.
//
// One report of the same class is suppressed by a frame below the top: Cyclone destroying a
// writer's condition variable (`ddsrt_cond_destroy`, when our RAII writer is deleted) while its
// `dq.builtins` thread broadcasts it under the entity's mutex; deletion waits for that thread with
// Cyclone's own atomics. Seen once in 4 TSan suites (`hubrt_dds_env_probe`, under
// TestDomainEnv.ChildProcessJoinsTheSameDomainOverLoopback), 0 in 80 runs of that test alone.
// `race:` matches any frame of either stack, and only Cyclone's function of that name: our own
// condition variables (std::condition_variable) stay reported.
//
// Compiled into each executable that uses DDS or cpp-httplib (TSan looks the function up in the
// main program).
#include "hubrt/base/sanitizers.h"

#if defined(HUBRT_SANITIZE_THREAD)
// NOLINTNEXTLINE(bugprone-reserved-identifier): the name TSan looks for.
extern "C" const char* __tsan_default_suppressions() {
  // Substring matches on the top frame's function name (anchors do not work for race_top).
  return "race_top:free\n"
         "race_top:malloc\n"
         "race_top:memcpy\n"
         "race_top:memcmp\n"
         "race_top:sendmsg\n"
         "race_top:recvmsg\n"
         "race_top:pthread_mutex_\n"
         "race:ddsrt_cond_destroy\n";
}
#endif
