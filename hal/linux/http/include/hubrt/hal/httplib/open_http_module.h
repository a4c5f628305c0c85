// The HTTP client of REST devices, loaded on demand: cpp-httplib lives in a module of its own,
// hubrt-http.so (Debian's libcpp-httplib is built with OpenSSL, zlib and brotli; initialising it
// costs every process that maps it ~2 MB of resident memory), so that only a hubd whose board
// declares an HTTP device loads it. Board packages of such boards install the module
// (packaging/cmake/HubrtBoardPackage.cmake).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/hal/http_client.h"

namespace hubrt::hal::httplib_client {

// Where the module is looked for, in order: <folder of the running program>/../lib/hubrt/
// hubrt-http.so (/usr/bin/hubd -> /usr/lib/hubrt/hubrt-http.so, and the same under any install
// prefix), then, in native builds only, the module of the build tree the program was built in.
std::vector<std::string> default_http_module_paths();

// A client for `config` from the first of `module_paths` that loads (hal/common/module_loader.h).
// Errors, naming the device: kUnavailable when no path loads (with every path tried and
// dlerror()'s reason), kInternal when a file loads but lacks the entry point (a module of another
// build), else those of open_httplib (open_httplib.h).
// Thread-safety: may be called from any thread (dlopen is).
Expected<std::unique_ptr<HttpClient>> open_http_module_client(const std::vector<std::string>& module_paths,
                                                              const HttpConfig& config);

}  // namespace hubrt::hal::httplib_client
