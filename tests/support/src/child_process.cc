#include "hubrt/test_support/child_process.h"

#include <elf.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include <sys/syscall.h>
#include <sys/wait.h>

extern char** environ;  // NOLINT(readability-redundant-declaration): POSIX declares it nowhere

namespace hubrt::test_support {
namespace {

std::string errno_text(int err) {
  return std::system_category().message(err);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A /proc stat line's fields from the third (the state) on: the command name before them may hold
// blanks and parentheses, so they start after its last ')'.
std::vector<std::string> stat_fields(const std::string& stat) {
  const auto name_end = stat.rfind(')');
  if (name_end == std::string::npos) return {};
  std::istringstream fields(stat.substr(name_end + 1));
  return {std::istream_iterator<std::string>(fields), std::istream_iterator<std::string>()};
}

// Owns posix_spawn's C structures for the duration of one spawn.
struct SpawnSetup {
  posix_spawn_file_actions_t actions{};
  posix_spawnattr_t attr{};
  SpawnSetup() {
    posix_spawn_file_actions_init(&actions);
    posix_spawnattr_init(&attr);
  }
  ~SpawnSetup() {
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
  }
  SpawnSetup(const SpawnSetup&) = delete;
  SpawnSetup& operator=(const SpawnSetup&) = delete;
};

std::vector<std::string> child_environment(const Environment& extra) {
  std::set<std::string> overridden;
  for (const auto& [name, value] : extra) overridden.insert(name);
  std::vector<std::string> env;
  for (char** entry = environ; entry != nullptr && *entry != nullptr; ++entry) {
    const std::string_view text(*entry);
    const std::string name(text.substr(0, text.find('=')));
    if (!overridden.contains(name)) env.emplace_back(text);
  }
  for (const auto& [name, value] : extra) {
    std::string entry = name;
    entry += '=';
    entry += value;
    env.push_back(std::move(entry));
  }
  return env;
}

std::vector<char*> as_argv(std::vector<std::string>& strings) {
  std::vector<char*> pointers;
  pointers.reserve(strings.size() + 1);
  for (std::string& s : strings) pointers.push_back(s.data());
  pointers.push_back(nullptr);
  return pointers;
}

// The e_machine field of an ELF file, or nullopt when `path` is not an ELF file (a script, a file
// that cannot be read). EI_DATA says the byte order; e_machine sits at the same offset in ELF32 and
// ELF64 headers.
std::optional<std::uint16_t> elf_machine(const std::string& path) {
  std::array<unsigned char, EI_NIDENT + 4> header{};
  std::ifstream in(path, std::ios::binary);
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-reinterpret-cast): istream reads chars
  if (!in.read(reinterpret_cast<char*>(header.data()), static_cast<std::streamsize>(header.size()))) {
    return std::nullopt;
  }
  if (header[EI_MAG0] != ELFMAG0 || header[EI_MAG1] != ELFMAG1 || header[EI_MAG2] != ELFMAG2 ||
      header[EI_MAG3] != ELFMAG3) {
    return std::nullopt;
  }
  const unsigned lo = header[EI_NIDENT + 2];
  const unsigned hi = header[EI_NIDENT + 3];
  if (header[EI_DATA] == ELFDATA2MSB) return static_cast<std::uint16_t>((lo << 8U) | hi);
  return static_cast<std::uint16_t>((hi << 8U) | lo);
}

// The machine this process's own code is for: under qemu-user /proc/self/exe is the emulated
// program, not qemu.
std::optional<std::uint16_t> own_machine() {
  static const std::optional<std::uint16_t> machine = elf_machine("/proc/self/exe");
  return machine;
}

// `name` looked up in PATH as execvp would: the first executable match, or empty.
std::string find_in_path(const std::string& name) {
  // NOLINTNEXTLINE(concurrency-mt-unsafe): see target_emulator()
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path != nullptr ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::string candidate = (dir.empty() ? std::string(".") : dir) + "/" + name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

ExitStatus to_exit_status(int wait_status) {
  ExitStatus status;
  if (WIFEXITED(wait_status)) status.exit_code = WEXITSTATUS(wait_status);
  if (WIFSIGNALED(wait_status)) status.term_signal = WTERMSIG(wait_status);
  return status;
}

}  // namespace

std::vector<std::string> target_emulator() {
  std::vector<std::string> words;
  // NOLINTNEXTLINE(concurrency-mt-unsafe): tests do not change the environment while spawning
  const char* value = std::getenv("HUBRT_TARGET_EMULATOR");
  if (value == nullptr) return words;
  std::istringstream in(value);
  for (std::string word; in >> word;) words.push_back(word);
  return words;
}

std::string ExitStatus::describe() const {
  if (exit_code) return "exit code " + std::to_string(*exit_code);
  if (term_signal)
    return "killed by signal " + std::to_string(*term_signal) + " (" + sigdescr_np(*term_signal) + ")";
  return "still running";
}

Expected<ChildProcess> ChildProcess::start(const std::string& program, const std::vector<std::string>& args,
                                           const Environment& extra_env, OutputMode output) {
  // qemu-user runs posix_spawn's vfork as a plain fork, so an exec that fails in the child looks
  // like a successful start: check what can be checked before spawning.
  const bool search_path = program.find('/') == std::string::npos;
  if (!search_path && ::access(program.c_str(), X_OK) != 0) {
    return make_error(ErrorCode::kIo, "start '" + program + "': " + errno_text(errno));
  }
  std::error_code ec;
  std::filesystem::path tmp = std::filesystem::temp_directory_path(ec);
  if (ec) tmp = "/tmp";
  std::string dir_template = (tmp / "hubrt-child-XXXXXX").string();
  if (::mkdtemp(dir_template.data()) == nullptr) {
    return make_error(ErrorCode::kIo, "start '" + program + "': cannot create output directory " +
                                          dir_template + ": " + errno_text(errno));
  }
  const std::string dir = dir_template;
  const std::string out_path = dir + "/stdout";
  const std::string err_path = dir + "/stderr";

  // Without binfmt_misc a program under qemu-user cannot exec a program for its own machine by
  // itself: such programs run as "<emulator words> program args". Host programs (/bin/sh) do not.
  std::vector<std::string> argv_strings = target_emulator();
  std::string to_spawn = program;
  if (!argv_strings.empty()) {
    const std::string resolved = search_path ? find_in_path(program) : program;
    const auto machine = resolved.empty() ? std::nullopt : elf_machine(resolved);
    if (machine && machine == own_machine()) {
      to_spawn = argv_strings.front();
      argv_strings.push_back(resolved);
    } else {
      argv_strings.clear();
    }
  }
  if (argv_strings.empty()) argv_strings.push_back(program);
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv = as_argv(argv_strings);
  std::vector<std::string> env_strings = child_environment(extra_env);
  std::vector<char*> envp = as_argv(env_strings);

  SpawnSetup setup;
  posix_spawn_file_actions_addopen(&setup.actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::array<int, 2> pipe_fds{-1, -1};
  if (output == OutputMode::kClosedPipe) {
    if (::pipe2(pipe_fds.data(), O_CLOEXEC) != 0) {
      const int err = errno;
      std::filesystem::remove_all(dir, ec);
      return make_error(ErrorCode::kIo, "start '" + program + "': pipe: " + errno_text(err));
    }
    // dup2 clears close-on-exec on the copies; the originals close at exec.
    posix_spawn_file_actions_adddup2(&setup.actions, pipe_fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&setup.actions, pipe_fds[1], STDERR_FILENO);
    ::close(pipe_fds[0]);  // no reader, from the start
  } else {
    posix_spawn_file_actions_addopen(&setup.actions, STDOUT_FILENO, out_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&setup.actions, STDERR_FILENO, err_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  // The child starts with no blocked signals and default dispositions for the ones tests send,
  // whatever the test runner set up for itself.
  sigset_t empty;
  sigemptyset(&empty);
  sigset_t defaults;
  sigemptyset(&defaults);
  for (const int sig : {SIGTERM, SIGINT, SIGHUP, SIGPIPE, SIGCHLD}) sigaddset(&defaults, sig);
  posix_spawnattr_setsigmask(&setup.attr, &empty);
  posix_spawnattr_setsigdefault(&setup.attr, &defaults);
  posix_spawnattr_setflags(&setup.attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);

  pid_t pid = -1;
  const int rc =
      to_spawn.find('/') == std::string::npos
          ? ::posix_spawnp(&pid, to_spawn.c_str(), &setup.actions, &setup.attr, argv.data(), envp.data())
          : ::posix_spawn(&pid, to_spawn.c_str(), &setup.actions, &setup.attr, argv.data(), envp.data());
  if (pipe_fds[1] >= 0) ::close(pipe_fds[1]);
  if (rc != 0) {
    std::filesystem::remove_all(dir, ec);
    return make_error(ErrorCode::kIo, "start '" + program + "': " + errno_text(rc));
  }
  return ChildProcess(pid, dir);
}

ChildProcess::~ChildProcess() {
  kill_and_reap();
  if (!dir_.empty()) {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
}

ChildProcess::ChildProcess(ChildProcess&& other) noexcept
    : pid_(std::exchange(other.pid_, -1)), dir_(std::exchange(other.dir_, {})) {}

ChildProcess& ChildProcess::operator=(ChildProcess&& other) noexcept {
  if (this != &other) {
    kill_and_reap();
    if (!dir_.empty()) {
      std::error_code ec;
      std::filesystem::remove_all(dir_, ec);
    }
    pid_ = std::exchange(other.pid_, -1);
    dir_ = std::exchange(other.dir_, {});
  }
  return *this;
}

void ChildProcess::kill_and_reap() noexcept {
  if (pid_ <= 0) return;
  (void)::kill(pid_, SIGKILL);
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
}

std::string ChildProcess::stdout_text() const {
  return dir_.empty() ? std::string() : read_file(dir_ + "/stdout");
}

std::string ChildProcess::stderr_text() const {
  return dir_.empty() ? std::string() : read_file(dir_ + "/stderr");
}

bool ChildProcess::has_exited() const noexcept {
  if (pid_ <= 0) return true;
  siginfo_t info{};
  // WNOWAIT: look without reaping, so that wait() still gets the exit status.
  if (::waitid(P_PID, static_cast<id_t>(pid_), &info, WEXITED | WNOHANG | WNOWAIT) != 0) return true;
  return info.si_pid != 0;
}

std::string ChildProcess::activity() const {
  if (pid_ <= 0) return "reaped";
  if (has_exited()) return "exited";
  const std::string proc = "/proc/" + std::to_string(pid_);
  const std::vector<std::string> field = stat_fields(read_file(proc + "/stat"));
  // field[0] is stat's field 3 (state); utime, stime and num_threads are fields 14, 15 and 20.
  if (field.size() < 18) return "still running (its /proc/" + std::to_string(pid_) + "/stat is unreadable)";
  const double cpu_seconds = static_cast<double>(std::stoull(field[11]) + std::stoull(field[12])) /
                             static_cast<double>(::sysconf(_SC_CLK_TCK));
  std::ostringstream text;
  text.precision(2);
  text << std::fixed << "still running: state " << field[0] << ", " << cpu_seconds << " s of CPU in "
       << field[17] << " thread(s)";
  // Each thread's name, state and wait channel (where the kernel shows it): which wait a stuck
  // start is in (a read of a network file system, a futex, a poll for a DNS answer).
  std::error_code error;
  std::vector<std::string> threads;
  for (const auto& task : std::filesystem::directory_iterator(proc + "/task", error)) {
    const std::string dir = task.path().string();
    const std::vector<std::string> task_field = stat_fields(read_file(dir + "/stat"));
    std::string name = read_file(dir + "/comm");
    if (!name.empty() && name.back() == '\n') name.pop_back();
    std::string thread = name + " " + (task_field.empty() ? std::string("?") : task_field[0]);
    const std::string wchan = read_file(dir + "/wchan");
    if (!wchan.empty() && wchan != "0") thread += " in " + wchan;
    threads.push_back(std::move(thread));
  }
  std::sort(threads.begin(), threads.end());
  constexpr std::size_t kThreadsShown = 24;
  for (std::size_t i = 0; i < threads.size() && i < kThreadsShown; ++i)
    text << (i == 0 ? ": " : ", ") << threads[i];
  if (threads.size() > kThreadsShown) text << ", ...";
  return text.str();
}

bool ChildProcess::wait_for_output(std::string_view needle, Duration timeout) const {
  // Polling files is the simplest readiness check that works for any child; 10 ms is far below
  // any start-up time we wait for.
  constexpr Duration kPollInterval = std::chrono::milliseconds(10);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  const auto contains = [&] {
    return stdout_text().find(needle) != std::string::npos || stderr_text().find(needle) != std::string::npos;
  };
  for (;;) {
    // Checked before the output so that output written just before exiting is still seen.
    const bool exited = has_exited();
    if (contains()) return true;
    if (exited) return false;
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) return false;
    std::this_thread::sleep_for(std::min<Duration>(kPollInterval, deadline - now));
  }
}

Expected<void> ChildProcess::signal(int sig) const {
  if (pid_ <= 0) return make_error(ErrorCode::kFailedPrecondition, "signal child: it was already reaped");
  if (::kill(pid_, sig) != 0) {
    return make_error(ErrorCode::kIo, "signal " + std::to_string(sig) + " to pid " + std::to_string(pid_) +
                                          ": " + errno_text(errno));
  }
  return {};
}

Expected<ExitStatus> ChildProcess::wait(Duration timeout) {
  if (pid_ <= 0) return make_error(ErrorCode::kFailedPrecondition, "wait for child: it was already reaped");
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + timeout;
  // A pidfd becomes readable when the child exits, so no polling is needed where the kernel has
  // them (Linux >= 5.3); elsewhere (old kernels, some emulators) fall back to polling.
  // Through syscall(2): bookworm's <sys/pidfd.h> lacks extern "C", so its wrapper does not link
  // from C++.
  const int pidfd = static_cast<int>(::syscall(SYS_pidfd_open, pid_, 0));
  for (;;) {
    int status = 0;
    const pid_t done = ::waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
      if (pidfd >= 0) ::close(pidfd);
      pid_ = -1;
      return to_exit_status(status);
    }
    if (done < 0 && errno != EINTR) {
      const int err = errno;
      if (pidfd >= 0) ::close(pidfd);
      return make_error(ErrorCode::kIo, "wait for pid " + std::to_string(pid_) + ": " + errno_text(err));
    }
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) {
      if (pidfd >= 0) ::close(pidfd);
      return make_error(ErrorCode::kTimeout, "pid " + std::to_string(pid_) + " still running after " +
                                                 std::to_string(to_seconds(now - start)) + " s");
    }
    const auto remaining = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now);
    if (pidfd >= 0) {
      pollfd fd{pidfd, POLLIN, 0};
      (void)::poll(&fd, 1, static_cast<int>(std::min<std::int64_t>(remaining.count() + 1, 1000)));
    } else {
      std::this_thread::sleep_for(std::min<Duration>(std::chrono::milliseconds(5), deadline - now));
    }
  }
}

}  // namespace hubrt::test_support
