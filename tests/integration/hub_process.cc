#include "hub_process.h"

#include <algorithm>

#include <fmt/format.h>

namespace hubrt::integration {

Expected<HubProcess> HubProcess::start(const test_support::TestDomain& domain,
                                       const HubProcessOptions& options) {
  std::vector<std::string> args = {"--board", options.board, "--hub", options.hub};
  args.insert(args.end(), options.extra_args.begin(), options.extra_args.end());
  test_support::Environment env = domain.env();
  // A variable in extra_env replaces the domain's (e.g. a CYCLONEDDS_URI with security): a
  // child's environment with the name twice would see only the first (getenv).
  std::erase_if(env, [&options](const auto& entry) {
    return std::any_of(options.extra_env.begin(), options.extra_env.end(),
                       [&entry](const auto& extra) { return extra.first == entry.first; });
  });
  env.insert(env.end(), options.extra_env.begin(), options.extra_env.end());
  env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
  auto child = test_support::ChildProcess::start(HUBRT_HUBD_PATH, args, env);
  if (!child) return std::move(child).error();
  if (!child->wait_for_output("running hub", std::chrono::seconds(20))) {
    return make_error(ErrorCode::kTimeout, fmt::format("hubd did not start; its output:\n{}{}",
                                                       child->stdout_text(), child->stderr_text()));
  }
  return HubProcess(std::move(*child));
}

Expected<Finished> run_hubd(const test_support::TestDomain& domain, const std::vector<std::string>& args,
                            Duration timeout, const test_support::Environment& extra_env) {
  test_support::Environment env = domain.env();
  const bool own_config_dir = std::any_of(extra_env.begin(), extra_env.end(), [](const auto& entry) {
    return entry.first == "HUBRT_CONFIG_DIR";
  });
  if (!own_config_dir) env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
  env.insert(env.end(), extra_env.begin(), extra_env.end());
  auto child = test_support::ChildProcess::start(HUBRT_HUBD_PATH, args, env);
  if (!child) return std::move(child).error();
  auto status = child->wait(timeout);
  if (!status) return std::move(status).error();
  return Finished{*status, child->stdout_text() + child->stderr_text()};
}

}  // namespace hubrt::integration
