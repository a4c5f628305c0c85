// A fresh temporary folder per test, removed afterwards, and the times the tests issue for.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "hubrt/security/pki.h"

namespace hubrt::security::test {

// A fixed "now" (2026-01-01T00:00:00Z): the checks take the time as an argument.
inline constexpr std::int64_t kNow = 1767225600;
inline constexpr std::int64_t kDay = 24 * 3600;

inline Validity year_around_now() {
  return Validity{kNow - kDay, kNow + 365 * kDay};
}

class TempFolder {
 public:
  TempFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "hubrt-security-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) ADD_FAILURE() << "mkdtemp failed";
    path_ = pattern;
  }
  ~TempFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace hubrt::security::test
