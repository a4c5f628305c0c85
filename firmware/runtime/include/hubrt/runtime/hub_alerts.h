// Conditions of the whole hub that every node reports in its State's error_list (and so in
// /diagnostics, where the hub's own status line shows the first one too), e.g. another process
// publishing this hub's States. Set by a cycle stage before the nodes step (today one stage owns
// them: the twin guard, which clears and refills them every cycle); read by the nodes when they
// rebuild their State. Fixed storage: never allocates.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

#include "hubrt/runtime/error_list.h"
#include "hubrt/runtime/text_buffer.h"

namespace hubrt::runtime {

// Thread-safety: cycle thread only, like the Hub that owns it.
class HubAlerts {
 public:
  static constexpr std::size_t kMaxAlerts = 4;

  void clear() noexcept { count_ = 0; }

  // Adds one alert; beyond kMaxAlerts the last one is overwritten (the stage that sets alerts
  // says "and N more" itself when it has more to say).
  template <class... Args>
  void add(fmt::format_string<Args...> spec, Args&&... args) noexcept {
    const std::size_t slot = count_ < kMaxAlerts ? count_++ : kMaxAlerts - 1;
    entries_[slot].format(spec, std::forward<Args>(args)...);
  }

  [[nodiscard]] std::size_t size() const noexcept { return count_; }
  [[nodiscard]] bool empty() const noexcept { return count_ == 0; }
  [[nodiscard]] std::string_view at(std::size_t i) const noexcept { return entries_[i].view(); }

 private:
  std::array<TextBuffer<ErrorList::kMaxLength>, kMaxAlerts> entries_{};
  std::size_t count_ = 0;
};

}  // namespace hubrt::runtime
