// The entry point of the MiR simulator's module, hubrt-mir-sim.so: its REST server runs on
// cpp-httplib (and through Debian's build of it OpenSSL), loaded only by a simulated hub whose
// board has a MiR (load_mir_sim_server.cc). Built from the same tree as its loader, so C++ types
// cross; the version in the name refuses a module of another build.
#include <exception>

#include "hubrt/hal/fake/mir_sim_server.h"

extern "C" __attribute__((visibility("default"))) void hubrt_mir_sim_module_start_v1(
    hubrt::hal::fake::MirPlatform& platform, const hubrt::Clock& clock,
    const hubrt::hal::fake::MirSimServerOptions& options,
    hubrt::Expected<std::unique_ptr<hubrt::hal::fake::MirSimServer>>& out) {
  try {  // no exception crosses the module boundary
    out = hubrt::hal::fake::start_mir_sim_server(platform, clock, options);
  } catch (const std::exception& e) {
    out = hubrt::make_error(hubrt::ErrorCode::kInternal, std::string("MiR simulator: ") + e.what());
  }
}
