#include "hubrt/test_support/hub_process.h"

#include <algorithm>
#include <cstdlib>

#include <fmt/format.h>

namespace hubrt::test_support {

std::string hubd_path() {
  const char* other = std::getenv("HUBRT_TEST_HUBD");
  return other != nullptr && other[0] != '\0' ? other : HUBRT_HUBD_PATH;
}

std::string config_dir() {
  const char* other = std::getenv("HUBRT_TEST_CONFIG_DIR");
  return other != nullptr && other[0] != '\0' ? other : HUBRT_SOURCE_DIR;
}

Expected<HubProcess> HubProcess::start(const TestDomain& domain, const HubProcessOptions& options) {
  std::vector<std::string> args = {"--board", options.board, "--hub", options.hub};
  args.insert(args.end(), options.extra_args.begin(), options.extra_args.end());
  Environment env = domain.env();
  // A variable in extra_env replaces the domain's (e.g. a CYCLONEDDS_URI with security): a
  // child's environment with the name twice would see only the first (getenv).
  std::erase_if(env, [&options](const auto& entry) {
    return std::any_of(options.extra_env.begin(), options.extra_env.end(),
                       [&entry](const auto& extra) { return extra.first == entry.first; });
  });
  env.insert(env.end(), options.extra_env.begin(), options.extra_env.end());
  env.emplace_back("HUBRT_CONFIG_DIR", config_dir());
  auto child = ChildProcess::start(hubd_path(), args, env, options.output);
  if (!child) return std::move(child).error();
  if (options.output == OutputMode::kClosedPipe) return HubProcess(std::move(*child));
  if (!child->wait_for_output("running hub", options.start_patience)) {
    return make_error(
        ErrorCode::kTimeout,
        fmt::format("hubd did not start within {} s ({}); its output:\n{}{}",
                    std::chrono::duration_cast<std::chrono::seconds>(options.start_patience).count(),
                    child->activity(), child->stdout_text(), child->stderr_text()));
  }
  return HubProcess(std::move(*child));
}

Expected<Finished> run_hubd(const TestDomain& domain, const std::vector<std::string>& args, Duration timeout,
                            const Environment& extra_env) {
  Environment env = domain.env();
  const bool own_config_dir = std::any_of(extra_env.begin(), extra_env.end(), [](const auto& entry) {
    return entry.first == "HUBRT_CONFIG_DIR";
  });
  if (!own_config_dir) env.emplace_back("HUBRT_CONFIG_DIR", config_dir());
  env.insert(env.end(), extra_env.begin(), extra_env.end());
  auto child = ChildProcess::start(hubd_path(), args, env);
  if (!child) return std::move(child).error();
  auto status = child->wait(timeout);
  if (!status) return std::move(status).error();
  return Finished{*status, child->stdout_text() + child->stderr_text()};
}

}  // namespace hubrt::test_support
