// The entry point of the HTTP client module, hubrt-http.so: cpp-httplib (and through Debian's
// build of it OpenSSL, zlib and brotli) is loaded only by a hubd that opens an HTTP device
// (load_http_module.cc), not by every hubd.
#include <exception>

#include "hubrt/hal/httplib/http_module_abi.h"
#include "hubrt/hal/httplib/open_httplib.h"

extern "C" __attribute__((visibility("default"))) void hubrt_http_module_open_v1(
    const hubrt::hal::HttpConfig& config, hubrt::Expected<std::unique_ptr<hubrt::hal::HttpClient>>& out) {
  // No exception crosses the module boundary (the loader is noexcept about it).
  try {
    out = hubrt::hal::httplib_client::open_httplib(config);
  } catch (const std::exception& e) {
    out = hubrt::make_error(hubrt::ErrorCode::kIo, config.device + ": " + e.what());
  }
}
