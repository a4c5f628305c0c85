#include "crash_handlers.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <exception>

#include "hubrt/blackbox/black_box.h"
#include "hubrt/hal/linux/crash_safe_outputs.h"

namespace hubrt::hubd {
namespace {

constexpr std::array<int, 5> kFatalSignals{SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT};

// Written once by install_crash_handlers() before any handler can run; read by the handlers.
std::array<struct sigaction, kFatalSignals.size()> g_previous{};
std::terminate_handler g_previous_terminate = nullptr;
std::atomic<blackbox::BlackBox*> g_black_box{nullptr};
static_assert(std::atomic<blackbox::BlackBox*>::is_always_lock_free, "read from a signal handler");

void say(const char* text) noexcept {
  std::size_t length = 0;
  while (text[length] != '\0') ++length;
  (void)::write(STDERR_FILENO, text, length);
}

void drive_safe_and_say(const char* why) noexcept {
  const hal::CrashSafeResult result = hal::drive_outputs_safe_from_crash();
  say("hubd: ");
  say(why);
  say(result.failed == 0 ? ": GPIO outputs driven to their safe levels\n"
                         : ": some GPIO outputs could NOT be driven to their safe levels\n");
  // The outputs first: writing the black box is the second thing a crash may still do.
  if (blackbox::BlackBox* box = g_black_box.load()) {
    box->crash_dump();
    say("hubd: black box written (its directory, *_crash.mcap)\n");
  }
}

void on_fatal_signal(int signal, siginfo_t* info, void* /*context*/) {
  drive_safe_and_say("fatal signal");
  for (std::size_t i = 0; i < kFatalSignals.size(); ++i) {
    if (kFatalSignals[i] == signal) ::sigaction(signal, &g_previous[i], nullptr);
  }
  // A fault (si_code > 0, from the kernel) happens again when the handler returns, now under the
  // old disposition, with its original details. A sent signal (kill, abort(): si_code <= 0) is
  // raised again; it is blocked here, so it arrives as soon as the handler returns.
  if (info == nullptr || info->si_code <= 0) ::raise(signal);
}

[[noreturn]] void on_terminate() {
  drive_safe_and_say("std::terminate");
  if (g_previous_terminate != nullptr) g_previous_terminate();
  std::abort();
}

}  // namespace

void set_crash_black_box(blackbox::BlackBox* box) noexcept {
  g_black_box.store(box);
}

void install_crash_handlers() {
  for (std::size_t i = 0; i < kFatalSignals.size(); ++i) {
    struct sigaction action {};
    action.sa_sigaction = on_fatal_signal;
    // On the alternate stack where one is set up (sanitizers do): a stack overflow leaves none.
    action.sa_flags = SA_SIGINFO | SA_ONSTACK;
    sigemptyset(&action.sa_mask);
    ::sigaction(kFatalSignals[i], &action, &g_previous[i]);
  }
  g_previous_terminate = std::set_terminate(on_terminate);
}

}  // namespace hubrt::hubd
