// What the HTTP client module (hubrt-http.so, built from src/http_module_entry.cc) and its loader
// (src/load_http_module.cc) agree on: the one symbol the module exports and its signature. Both
// are built from the same tree with the same compiler and libstdc++, so C++ types may cross; the
// version in the name refuses a module of another build whose signature differs.
#pragma once

#include <memory>

#include "hubrt/base/status.h"
#include "hubrt/hal/http_client.h"

namespace hubrt::hal::httplib_client {

// The module's file name: next to hubd as <prefix>/lib/hubrt/hubrt-http.so.
inline constexpr const char* kHttpModuleFileName = "hubrt-http.so";
// extern "C" void hubrt_http_module_open_v1(const HttpConfig&, Expected<std::unique_ptr<HttpClient>>&)
inline constexpr const char* kHttpModuleOpenSymbol = "hubrt_http_module_open_v1";
using HttpModuleOpenFn = void (*)(const HttpConfig& config, Expected<std::unique_ptr<HttpClient>>& out);

}  // namespace hubrt::hal::httplib_client
