// UndefinedBehaviorSanitizer's defaults for the programs of a sanitizer build (hubd, hubctl, hubsim,
// hubbridge and the tests that link the TSan suppressions beside this file): print where the
// undefined behaviour happened. Its default prints only the offending line, which in a header
// (basic_string.h, say) does not say whose call it was: a report from a hubd run inside the kernel
// tier's VM, once, under load, was only that. UBSAN_OPTIONS still overrides it flag by flag.
#include "hubrt/base/sanitizers.h"

#if defined(HUBRT_SANITIZE_UNDEFINED)
// NOLINTNEXTLINE(bugprone-reserved-identifier): the name UBSan looks for.
extern "C" const char* __ubsan_default_options() {
  return "print_stacktrace=1";
}
#endif
