// Starting a program (hubd, a probe) from a test, watching its output and stopping it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <sys/types.h>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/test_support/test_domain.h"

namespace hubrt::test_support {

// How a child ended: exit code or the signal that killed it.
struct ExitStatus {
  std::optional<int> exit_code;    // set when it exited
  std::optional<int> term_signal;  // set when a signal ended it

  [[nodiscard]] bool exited_with(int code) const noexcept { return exit_code == code; }
  [[nodiscard]] bool killed_by(int signal) const noexcept { return term_signal == signal; }
  // "exit code 3" / "killed by signal 15 (Terminated)".
  [[nodiscard]] std::string describe() const;
};

// Where a child's stdout and stderr go.
enum class OutputMode : std::uint8_t {
  kFiles,       // files in a private directory (stdout_text(), stderr_text())
  kClosedPipe,  // a pipe whose reading end is closed before the child runs: every write to them
                // fails (EPIPE, and SIGPIPE unless the child ignores it), as for `prog | head -0`
};

// A child process whose stdout and stderr go to files in a private temporary directory (files,
// not pipes, so a chatty child never blocks on a full pipe and the output survives for the
// failure message). stdin is /dev/null. Move-only.
// The destructor kills a child that still runs (SIGKILL to its own PID only), reaps it and
// removes the output files.
// Thread-safety: none; use from one thread.
class ChildProcess {
 public:
  // Starts `program` (a path, or a name looked up in PATH if it contains no '/') with `args`
  // (argv[1..]) and the current environment plus `extra_env` (which overrides same-named
  // variables).
  // Cross builds: when the environment variable HUBRT_TARGET_EMULATOR is set (space-separated
  // words, e.g. "qemu-aarch64-static -L <sysroot>", which cross-built tests get from CTest) and
  // `program` is an ELF file for the same machine as this process, it runs as
  // "<emulator words> <program> args" (qemu-user without binfmt_misc cannot exec it otherwise);
  // host programs such as /bin/sh and scripts run directly.
  // Errors: kIo naming the program when a path is not an executable file (checked before
  // spawning: under qemu-user a failed exec would look like a successful start), the output
  // directory cannot be made or spawning fails.
  // `output`: see OutputMode (with kClosedPipe the output texts stay empty).
  static Expected<ChildProcess> start(const std::string& program, const std::vector<std::string>& args,
                                      const Environment& extra_env = {},
                                      OutputMode output = OutputMode::kFiles);

  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&& other) noexcept;

  [[nodiscard]] pid_t pid() const noexcept { return pid_; }
  // Everything the child wrote so far.
  [[nodiscard]] std::string stdout_text() const;
  [[nodiscard]] std::string stderr_text() const;

  // Polls stdout and stderr until one contains `needle` (true), or until `timeout` passes or the
  // child has exited without writing it (false). Does not reap the child.
  bool wait_for_output(std::string_view needle, Duration timeout) const;

  // What the child is doing, for a failure message after a wait for it gave up: "exited" (not
  // yet reaped), or from /proc "still running: state S, 0.42 s of CPU in 2 thread(s): hubd S in
  // do_sys_poll, recvUC S in ..." (each thread's name, state and, where the kernel shows it, wait
  // channel). A slow start uses CPU; a stuck one does not, and its waits say on what.
  [[nodiscard]] std::string activity() const;

  // Sends `signal` to the child. Errors: kFailedPrecondition if it was already reaped.
  Expected<void> signal(int sig) const;

  // Waits for the child to end and reaps it. Errors: kTimeout if it still runs after
  // `timeout` (it keeps running); kFailedPrecondition if already reaped.
  Expected<ExitStatus> wait(Duration timeout);

 private:
  ChildProcess(pid_t pid, std::string dir) noexcept : pid_(pid), dir_(std::move(dir)) {}
  void kill_and_reap() noexcept;
  [[nodiscard]] bool has_exited() const noexcept;

  pid_t pid_ = -1;  // -1 once reaped
  std::string dir_;
};

// HUBRT_TARGET_EMULATOR split into words: the cross tier runs the target's programs under
// qemu-user (slow, and a host program such as unshare cannot exec them by itself); empty in
// native builds. ChildProcess::start puts these words in front of target programs itself.
std::vector<std::string> target_emulator();

}  // namespace hubrt::test_support
