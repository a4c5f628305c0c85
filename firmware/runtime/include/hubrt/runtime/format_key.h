// What a formatted message was made of — its format string and the values of its arguments,
// copied into fixed storage — so that a message rebuilt every cycle is formatted again only when
// one of them changed (ErrorList). Comparing a key costs a copy and a memcmp of a few hundred
// bytes; formatting and checking the message's UTF-8 cost several times that, every cycle, for
// an error that stays the same for hours (a missing device).
//
// Exact, not a hash: two keys are equal only when the format strings are the same text and every
// argument has the same kind, size and bytes (a string argument: its length and its characters,
// read now, so a buffer changed in place is seen). Numbers and std::string, std::string_view and C
// strings have keys; an argument of any other type (one with its own fmt::formatter), or
// arguments too large for the storage, make the key unusable: such a message is formatted every
// time, as without a key. Never allocates.
#pragma once

#include <array>
#include <cstddef>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

namespace hubrt::runtime {

template <std::size_t Capacity>
class FormatKey {
 public:
  // User-provided, so that a value-initialised key (std::array<FormatKey, N> keys{}) leaves its
  // storage untouched rather than zeroing it.
  FormatKey() noexcept {}  // NOLINT(modernize-use-equals-default)

  // Makes this the key of (spec, args) and returns true when it was that already: the message
  // these would format is the one formatted when the key was last set. False when it changed, or
  // when (spec, args) has no key (see above; the key is then unusable until set again).
  template <class... Args>
  bool update(std::string_view spec, const Args&... args) noexcept {
    Writer next;
    next.put_string(spec);
    (next.put(args), ...);
    if (!next.ok) {
      usable_ = false;
      return false;
    }
    const bool same =
        usable_ && next.size == size_ && std::memcmp(next.bytes.data(), bytes_.data(), size_) == 0;
    if (!same) {
      std::memcpy(bytes_.data(), next.bytes.data(), next.size);
      size_ = next.size;
      usable_ = true;
    }
    return same;
  }

  // The message no longer is what the key says (it was overwritten by other means).
  void forget() noexcept { usable_ = false; }

 private:
  template <class U>
  static constexpr char arithmetic_kind() noexcept {
    if constexpr (std::is_same_v<U, bool>) return 'b';
    if constexpr (std::is_same_v<U, char> || std::is_same_v<U, wchar_t> || std::is_same_v<U, char8_t> ||
                  std::is_same_v<U, char16_t> || std::is_same_v<U, char32_t>)
      return 'c';
    if constexpr (std::is_floating_point_v<U>) return 'f';
    return std::is_signed_v<U> ? 'i' : 'u';
  }

  struct Writer {
    std::array<unsigned char, Capacity> bytes;  // not initialised: only the first `size` are used
    std::size_t size = 0;
    bool ok = true;

    void put_bytes(const void* data, std::size_t n) noexcept {
      if (!ok || n > Capacity - size) {
        ok = false;
        return;
      }
      if (n > 0) std::memcpy(bytes.data() + size, data, n);
      size += n;
    }
    void put_tag(char kind, std::size_t n) noexcept {
      const unsigned char tag[2] = {static_cast<unsigned char>(kind), static_cast<unsigned char>(n)};
      put_bytes(tag, sizeof tag);
    }
    void put_string(std::string_view text) noexcept {
      const std::size_t length = text.size();
      put_tag('s', sizeof length);
      put_bytes(&length, sizeof length);
      put_bytes(text.data(), length);
    }
    template <class T>
    void put(const T& value) noexcept {
      using U = std::remove_cvref_t<T>;
      if constexpr (std::is_arithmetic_v<U>) {
        // The value's own bytes, under a tag of its kind (the same bytes are -1 as an int and
        // 4294967295 as an unsigned): a number formats the same text whenever kind, size and bytes
        // are the same (a NaN's too); different bytes only mean formatting again.
        put_tag(arithmetic_kind<U>(), sizeof(U));
        put_bytes(&value, sizeof(U));
      } else if constexpr (std::is_pointer_v<U> &&
                           std::is_same_v<std::remove_cv_t<std::remove_pointer_t<U>>, char>) {
        if (value == nullptr) {
          ok = false;  // fmt refuses a null C string; let it say so
          return;
        }
        put_string(std::string_view(value));
      } else if constexpr (std::is_same_v<U, std::string> || std::is_same_v<U, std::string_view> ||
                           (std::is_array_v<U> &&
                            std::is_same_v<std::remove_cv_t<std::remove_extent_t<U>>, char>)) {
        // Exactly these: fmt formats their characters. A class that merely converts to a string
        // may have a formatter of its own that says something else.
        put_string(std::string_view(value));
      } else {
        ok = false;  // formatted by a formatter of its own: no key
      }
    }
  };

  // Not initialised: only the first size_ bytes are ever read, once written; so a list's keys
  // occupy memory only as far as messages have used them.
  std::array<unsigned char, Capacity> bytes_;
  std::size_t size_ = 0;
  bool usable_ = false;
};

}  // namespace hubrt::runtime
