#include "launched_hub.h"

#include <signal.h>
#include <spawn.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <map>
#include <thread>

#include <fmt/format.h>
#include <sys/wait.h>

#include "state_stream.h"

extern char** environ;  // NOLINT: POSIX

namespace hubrt::hubctl {
namespace {

std::string describe_status(int status) {
  if (WIFEXITED(status)) return fmt::format("exit code {}", WEXITSTATUS(status));
  if (WIFSIGNALED(status))
    return fmt::format("killed by signal {} ({})", WTERMSIG(status), strsignal(WTERMSIG(status)));
  return "ended";
}

}  // namespace

Expected<LaunchedHub> LaunchedHub::start(const std::string& command,
                                         const std::vector<std::pair<std::string, std::string>>& extra_env) {
  std::map<std::string, std::string> env;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry(*e);
    const auto eq = entry.find('=');
    if (eq != std::string::npos) env[entry.substr(0, eq)] = entry.substr(eq + 1);
  }
  for (const auto& [name, value] : extra_env) env[name] = value;
  std::vector<std::string> env_text;
  for (const auto& [name, value] : env) env_text.push_back(name + "=" + value);
  std::vector<char*> envp;
  for (std::string& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);

  std::string script = "exec " + command;
  std::string shell = "/bin/sh";
  std::string dash_c = "-c";
  std::vector<char*> argv{shell.data(), dash_c.data(), script.data(), nullptr};

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  // The hub's stdout joins hubctl's stderr: stdout carries the report (and --json).
  posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  // hubctl blocks nothing, but reset the mask anyway so the hub sees SIGTERM however we were started.
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  pid_t pid = -1;
  const double started = steady_seconds();
  const int rc = posix_spawn(&pid, shell.c_str(), &actions, &attributes, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (rc != 0) {
    return make_error(ErrorCode::kIo, fmt::format("cannot start '{}': {}", command, std::strerror(rc)));
  }
  return LaunchedHub(pid, started);
}

LaunchedHub::LaunchedHub(LaunchedHub&& other) noexcept
    : pid_(std::exchange(other.pid_, -1)), started_at_s_(other.started_at_s_), end_(std::move(other.end_)) {}

LaunchedHub::~LaunchedHub() {
  if (pid_ > 0) stop();
}

std::string LaunchedHub::ended() noexcept {
  if (pid_ > 0) {
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      end_ = describe_status(status);
      pid_ = -1;
    }
  }
  return end_;
}

std::string LaunchedHub::stop(double grace_s) noexcept {
  if (pid_ <= 0) return end_;
  if (!ended().empty()) return end_;
  kill(pid_, SIGTERM);
  const double deadline = steady_seconds() + grace_s;
  while (steady_seconds() < deadline) {
    if (!ended().empty()) return end_;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid_, SIGKILL);
  int status = 0;
  if (waitpid(pid_, &status, 0) == pid_) end_ = describe_status(status);
  pid_ = -1;
  return end_;
}

}  // namespace hubrt::hubctl
