#include <fmt/format.h>

#include "hubrt/hal/common/module_loader.h"
#include "hubrt/hal/fake/mir_sim_server.h"

namespace hubrt::hal::fake {
namespace {

constexpr const char* kMirSimModuleFileName = "hubrt-mir-sim.so";
// The signature of the entry point in mir_sim_module_entry.cc.
constexpr const char* kMirSimStartSymbol = "hubrt_mir_sim_module_start_v1";
using MirSimStartFn = void (*)(MirPlatform& platform, const Clock& clock, const MirSimServerOptions& options,
                               Expected<std::unique_ptr<MirSimServer>>& out);

}  // namespace

std::vector<std::string> default_mir_sim_module_paths() {
  // HUBRT_MIR_SIM_MODULE_BUILD_PATH (CMakeLists.txt): the build tree's module, empty when cross.
  return {program_relative_module_path(kMirSimModuleFileName), HUBRT_MIR_SIM_MODULE_BUILD_PATH};
}

Expected<std::unique_ptr<MirSimServer>> load_mir_sim_server(const std::vector<std::string>& module_paths,
                                                            MirPlatform& platform, const Clock& clock,
                                                            const MirSimServerOptions& options) {
  auto symbol = load_module_symbol(module_paths, kMirSimModuleFileName, kMirSimStartSymbol);
  if (!symbol) {
    Error error = std::move(symbol).error();
    error.message = fmt::format("MiR simulator: {}", error.message);
    return error;
  }
  // POSIX: dlsym's void* is the function's address (the signature above).
  auto* start = reinterpret_cast<MirSimStartFn>(*symbol);
  Expected<std::unique_ptr<MirSimServer>> server = make_error(
      ErrorCode::kInternal, fmt::format("MiR simulator: {} gave no answer", kMirSimModuleFileName));
  start(platform, clock, options, server);
  return server;
}

}  // namespace hubrt::hal::fake
