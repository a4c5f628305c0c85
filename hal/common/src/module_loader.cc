#include "hubrt/hal/common/module_loader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <array>
#include <filesystem>

#include <fmt/format.h>

namespace hubrt::hal {

std::string program_relative_module_path(std::string_view file_name) {
  std::array<char, 4096> exe{};
  const ssize_t length = ::readlink("/proc/self/exe", exe.data(), exe.size() - 1);
  if (length <= 0) return {};
  const std::filesystem::path program(std::string(exe.data(), static_cast<std::size_t>(length)));
  return (program.parent_path().parent_path() / "lib" / "hubrt" / file_name).string();
}

Expected<void*> load_module_symbol(const std::vector<std::string>& paths, std::string_view file_name,
                                   const char* symbol) {
  std::string tried;
  for (const std::string& path : paths) {
    if (path.empty()) continue;
    // Never dlclose()d: objects the module made run its code. Opening it again counts a reference.
    void* module = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (module == nullptr) {
      // NOLINTNEXTLINE(concurrency-mt-unsafe): glibc keeps dlerror()'s state per thread (dlerror(3)).
      const char* why = ::dlerror();
      tried += fmt::format("; {}", why != nullptr ? why : path);
      continue;
    }
    void* address = ::dlsym(module, symbol);
    if (address == nullptr) {
      return make_error(ErrorCode::kInternal,
                        fmt::format("{} has no {} (a module of another hubrt build?)", path, symbol));
    }
    return address;
  }
  return make_error(ErrorCode::kUnavailable, fmt::format("the module {} is not installed{}", file_name,
                                                         tried.empty() ? "; no path to look in" : tried));
}

}  // namespace hubrt::hal
