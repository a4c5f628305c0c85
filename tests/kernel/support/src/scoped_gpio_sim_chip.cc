#include <fcntl.h>
#include <spawn.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <system_error>
#include <utility>
#include <vector>

#include <sys/wait.h>

#include "hubrt/kernel_test/gpio_sim.h"

extern char** environ;  // NOLINT(readability-redundant-declaration): POSIX, for posix_spawn

namespace hubrt::kernel_test {
namespace {

struct HelperRun {
  int exit_status = -1;
  std::string output;  // stdout and stderr together
};

// Runs the tier's gpiosim helper with `args` (no shell involved) and collects its output.
Expected<HelperRun> run_helper(const std::vector<std::string>& args) {
  const char* helper = std::getenv("HUBRT_GPIOSIM_HELPER");  // NOLINT(concurrency-mt-unsafe): read-only env
  if (!in_kernel_tier() || helper == nullptr) {
    return make_error(ErrorCode::kFailedPrecondition, std::string("gpiosim helper: ") + kNotInKernelTier);
  }
  std::array<int, 2> pipe_fds{};
  if (::pipe2(pipe_fds.data(), O_CLOEXEC) != 0) {
    return make_error(ErrorCode::kIo, "gpiosim helper: pipe: " + std::generic_category().message(errno));
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
  std::vector<std::string> argv_storage{helper};
  argv_storage.insert(argv_storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  argv.reserve(argv_storage.size() + 1);
  for (auto& arg : argv_storage) argv.push_back(arg.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawn_error = posix_spawn(&pid, helper, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  if (spawn_error != 0) {
    ::close(pipe_fds[0]);
    return make_error(ErrorCode::kIo, std::string("gpiosim helper ") + helper + ": " +
                                          std::generic_category().message(spawn_error));
  }
  HelperRun run;
  std::array<char, 512> buffer{};
  for (;;) {
    const ssize_t got = ::read(pipe_fds[0], buffer.data(), buffer.size());
    if (got > 0) {
      run.output.append(buffer.data(), static_cast<std::size_t>(got));
    } else if (got == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  run.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return run;
}

// The helper prints HUBRT_GPIOSIM_<FIELD>=value lines (see guest/gpiosim).
Expected<GpioSimChip> chip_from_helper_output(const std::string& output) {
  GpioSimChip chip;
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    const auto equals = line.find('=');
    if (equals == std::string::npos) continue;
    const std::string key = line.substr(0, equals);
    const std::string value = line.substr(equals + 1);
    if (key == "HUBRT_GPIOSIM_CHIP") chip.name = value;
    if (key == "HUBRT_GPIOSIM_DEV") chip.dev_path = value;
    if (key == "HUBRT_GPIOSIM_SYSFS") chip.sysfs_dir = value;
    if (key == "HUBRT_GPIOSIM_LABEL") chip.label = value;
    if (key == "HUBRT_GPIOSIM_LINES") {
      std::from_chars(value.data(), value.data() + value.size(), chip.num_lines);
    }
  }
  if (chip.name.empty() || chip.dev_path.empty() || chip.sysfs_dir.empty() || chip.num_lines == 0) {
    return make_error(ErrorCode::kProtocol, "gpiosim helper: incomplete description: " + output);
  }
  return chip;
}

}  // namespace

Expected<ScopedGpioSimChip> ScopedGpioSimChip::create(const std::string& name, unsigned num_lines,
                                                      const std::map<unsigned, std::string>& line_names) {
  std::vector<std::string> args{"create", name, std::to_string(num_lines)};
  for (const auto& [offset, line_name] : line_names) args.push_back(std::to_string(offset) + "=" + line_name);
  auto run = run_helper(args);
  if (!run) return std::move(run).error();
  if (run->exit_status != 0) {
    return make_error(ErrorCode::kIo, "gpio-sim chip " + name + ": helper exited with " +
                                          std::to_string(run->exit_status) + ": " + run->output);
  }
  auto chip = chip_from_helper_output(run->output);
  if (!chip) return std::move(chip).error();
  return ScopedGpioSimChip(name, std::move(*chip));
}

ScopedGpioSimChip::ScopedGpioSimChip(ScopedGpioSimChip&& other) noexcept
    : configfs_name_(std::exchange(other.configfs_name_, {})), chip_(std::move(other.chip_)) {}

ScopedGpioSimChip& ScopedGpioSimChip::operator=(ScopedGpioSimChip&& other) noexcept {
  if (this != &other) {
    ScopedGpioSimChip old(std::move(*this));
    configfs_name_ = std::exchange(other.configfs_name_, {});
    chip_ = std::move(other.chip_);
  }
  return *this;
}

ScopedGpioSimChip::~ScopedGpioSimChip() {
  if (configfs_name_.empty()) return;
  auto run = run_helper({"remove", configfs_name_});
  if (!run) {
    std::fprintf(stderr, "ScopedGpioSimChip: %s\n", run.error().message.c_str());
  } else if (run->exit_status != 0) {
    std::fprintf(stderr, "ScopedGpioSimChip: removing %s failed: %s\n", configfs_name_.c_str(),
                 run->output.c_str());
  }
}

}  // namespace hubrt::kernel_test
