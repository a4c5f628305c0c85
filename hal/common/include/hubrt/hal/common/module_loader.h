// Device code that pulls in a large library only some hubs need lives in a module of its own
// (a shared object opened with dlopen when a device needs it), e.g. the HTTP client of REST
// devices, hubrt-http.so: a hub without such a device never maps the library. This finds and
// opens such modules.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"

namespace hubrt::hal {

// <folder of the running program>/../lib/hubrt/<file_name> (/usr/bin/hubd ->
// /usr/lib/hubrt/<file_name>, the same under any install prefix); empty when /proc/self/exe
// cannot be read. Thread-safe.
std::string program_relative_module_path(std::string_view file_name);

// The address of `symbol` in the first of `paths` that dlopen (RTLD_NOW | RTLD_LOCAL) loads. The
// module stays loaded for the rest of the process (what it made runs its code).
// Errors: kUnavailable when no path loads (the message names `file_name`, each path tried and
// dlerror()'s reason), kInternal when one loads but lacks `symbol` (a module of another build).
// Thread-safe (dlopen, dlsym and dlerror are, per thread).
Expected<void*> load_module_symbol(const std::vector<std::string>& paths, std::string_view file_name,
                                   const char* symbol);

}  // namespace hubrt::hal
