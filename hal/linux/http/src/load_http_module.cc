#include <fmt/format.h>

#include "hubrt/hal/common/module_loader.h"
#include "hubrt/hal/httplib/http_module_abi.h"
#include "hubrt/hal/httplib/open_http_module.h"

namespace hubrt::hal::httplib_client {

std::vector<std::string> default_http_module_paths() {
  // HUBRT_HTTP_MODULE_BUILD_PATH (CMakeLists.txt): the module in the build tree for native builds,
  // empty for cross builds (their tree is not on the board).
  return {program_relative_module_path(kHttpModuleFileName), HUBRT_HTTP_MODULE_BUILD_PATH};
}

Expected<std::unique_ptr<HttpClient>> open_http_module_client(const std::vector<std::string>& module_paths,
                                                              const HttpConfig& config) {
  auto symbol = load_module_symbol(module_paths, kHttpModuleFileName, kHttpModuleOpenSymbol);
  if (!symbol) {
    Error error = std::move(symbol).error();
    if (error.code == ErrorCode::kUnavailable) {
      error.message += " (the board package of a board with http devices installs it)";
    }
    error.message = fmt::format("{}: {}", describe_http(config), error.message);
    return error;
  }
  // POSIX: dlsym's void* is the function's address (the signature is the ABI header's).
  auto* open = reinterpret_cast<HttpModuleOpenFn>(*symbol);
  Expected<std::unique_ptr<HttpClient>> client = make_error(
      ErrorCode::kInternal, fmt::format("{}: {} gave no answer", describe_http(config), kHttpModuleFileName));
  open(config, client);
  return client;
}

}  // namespace hubrt::hal::httplib_client
