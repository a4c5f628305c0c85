// The pieces the generated typed accessors (<idl>_typed.h, see firmware/msgs/README.md) are made
// of: bounded strings read as std::string_view and written by a truncating copy, and bounded
// sequences over storage sized at their bound. Nothing here allocates; every call is noexcept.
//
// idlc's C layout (Cyclone DDS 0.10): IDL string<N> is `char[N+1]` inline; sequence<T, N> is
// `struct { uint32_t _maximum, _length; T* _buffer; bool _release; }` (for T = string<M>, the
// buffer is `char (*)[M+1]`). The generated owning types point `_buffer` at their own storage.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string_view>
#include <type_traits>

namespace hubrt::msgs::typed {

// The longest prefix of `text` of at most `max_bytes` bytes that does not cut a UTF-8 sequence
// in two: when the cut would fall after a lead byte or inside a multi-byte character, that
// character is left out whole. (Bytes that are not UTF-8 at all are cut like any other.)
constexpr std::string_view utf8_prefix(std::string_view text, std::size_t max_bytes) noexcept {
  if (text.size() <= max_bytes) return text;
  std::size_t cut = max_bytes;
  // text[cut] is the first byte left out: while it continues a character, that character
  // started before the cut, so cut before its lead byte.
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0u) == 0x80u) --cut;
  return text.substr(0, cut);
}

// The text of a bounded string (up to its NUL; all N+1 bytes if a peer sent none, which Cyclone's
// deserialiser does not let through).
template <std::size_t Size>
std::string_view view(const char (&stored)[Size]) noexcept {
  return {stored, ::strnlen(stored, Size)};
}

// Copies `text` into a bounded string, cut at Size-1 bytes on a UTF-8 boundary (utf8_prefix).
// Returns false when the text was cut.
template <std::size_t Size>
bool assign(char (&stored)[Size], std::string_view text) noexcept {
  const std::string_view kept = utf8_prefix(text, Size - 1);
  if (!kept.empty()) std::memcpy(stored, kept.data(), kept.size());  // an empty view may hold nullptr
  std::memset(stored + kept.size(), 0, Size - kept.size());
  return kept.size() == text.size();
}

// A bounded string inside a sequence, read and written in place.
template <std::size_t Size>
class StringRef {
 public:
  explicit StringRef(char (&stored)[Size]) noexcept : stored_(&stored) {}
  [[nodiscard]] std::string_view view() const noexcept { return typed::view(*stored_); }
  operator std::string_view() const noexcept { return view(); }  // NOLINT: reads like a string
  bool assign(std::string_view text) const noexcept { return typed::assign(*stored_, text); }

 private:
  char (*stored_)[Size];
};

// How a sequence's elements are read (View) and written (Ref), per element kind.
template <class T>
struct ScalarElement {
  using Stored = T;
  using View = T;
  using Ref = T&;
  static View view(const Stored& s) noexcept { return s; }
  static Ref ref(Stored& s) noexcept { return s; }
  static void assign(Stored& s, T value) noexcept { s = value; }
};

template <std::size_t N>  // IDL string<N>
struct StringElement {
  using Stored = char[N + 1];
  using View = std::string_view;
  using Ref = StringRef<N + 1>;
  static View view(const Stored& s) noexcept { return typed::view(s); }
  static Ref ref(Stored& s) noexcept { return Ref(s); }
  static void assign(Stored& s, std::string_view text) noexcept { typed::assign(s, text); }
};

template <class ElementView, class ElementRef>  // a generated struct's View and Ref
struct StructElement {
  using Stored = typename ElementView::Wire;
  using View = ElementView;
  using Ref = ElementRef;
  static View view(const Stored& s) noexcept { return View(s); }
  static Ref ref(Stored& s) noexcept { return Ref(s); }
  static void assign(Stored& s, const View& value) noexcept { s = value.wire(); }
};

// Index iterator over a sequence, yielding what `Access` gives for element i.
template <class Owner, class Value>
class IndexIterator {
 public:
  IndexIterator(const Owner* owner, std::size_t i) noexcept : owner_(owner), i_(i) {}
  Value operator*() const noexcept { return (*owner_)[i_]; }
  IndexIterator& operator++() noexcept {
    ++i_;
    return *this;
  }
  bool operator==(const IndexIterator& other) const noexcept { return i_ == other.i_; }

 private:
  const Owner* owner_;
  std::size_t i_;
};

// A sequence field, read-only.
template <class Traits>
class SequenceView {
 public:
  using Stored = typename Traits::Stored;
  SequenceView(const Stored* data, std::uint32_t length) noexcept
      : data_(data), size_(data == nullptr ? 0 : length) {}
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] bool empty() const noexcept { return size_ == 0; }
  // Precondition: i < size().
  typename Traits::View operator[](std::size_t i) const noexcept { return Traits::view(data_[i]); }
  [[nodiscard]] IndexIterator<SequenceView, typename Traits::View> begin() const noexcept {
    return {this, 0};
  }
  [[nodiscard]] IndexIterator<SequenceView, typename Traits::View> end() const noexcept {
    return {this, size_};
  }

 private:
  const Stored* data_;
  std::size_t size_;
};

// A sequence field of a message whose storage was sized at construction (a generated owning
// type binds `_buffer` to `Bound` elements of its own): grows and shrinks within that storage,
// never allocates. Over a sample nobody bound (`_maximum` 0), it holds nothing and refuses to grow.
template <class Traits, std::size_t Bound, class Sequence>
class SequenceRef {
 public:
  using Stored = typename Traits::Stored;
  explicit SequenceRef(Sequence& seq) noexcept : seq_(&seq) {}

  [[nodiscard]] std::size_t size() const noexcept { return seq_->_length; }
  [[nodiscard]] bool empty() const noexcept { return seq_->_length == 0; }
  // The IDL bound, or less when the storage behind this sample is smaller.
  [[nodiscard]] std::size_t capacity() const noexcept {
    return seq_->_buffer == nullptr ? 0 : std::min<std::size_t>(Bound, seq_->_maximum);
  }
  [[nodiscard]] bool full() const noexcept { return size() >= capacity(); }
  // Precondition: i < size().
  typename Traits::Ref operator[](std::size_t i) const noexcept { return Traits::ref(seq_->_buffer[i]); }
  [[nodiscard]] IndexIterator<SequenceRef, typename Traits::Ref> begin() const noexcept { return {this, 0}; }
  [[nodiscard]] IndexIterator<SequenceRef, typename Traits::Ref> end() const noexcept {
    return {this, size()};
  }
  operator SequenceView<Traits>() const noexcept {  // NOLINT: a writable sequence is readable
    return SequenceView<Traits>(seq_->_buffer, seq_->_length);
  }

  void clear() const noexcept { seq_->_length = 0; }
  // Makes the sequence `n` elements long; new elements are zero ("" and 0). Returns false (and
  // stops at capacity()) when `n` does not fit.
  bool resize(std::size_t n) const noexcept {
    const std::size_t kept = std::min(n, capacity());
    for (std::size_t i = size(); i < kept; ++i) std::memset(&seq_->_buffer[i], 0, sizeof(Stored));
    seq_->_length = static_cast<std::uint32_t>(kept);
    return kept == n;
  }
  // Appends a copy of `value` (a string is cut like assign()). Returns false when full.
  template <class Value>
  bool push_back(const Value& value) const noexcept {
    if (full()) return false;
    Traits::assign(seq_->_buffer[seq_->_length], value);
    ++seq_->_length;
    return true;
  }
  // Appends a zeroed element and gives it to be filled; nothing when full.
  std::optional<typename Traits::Ref> append() const noexcept {
    if (full()) return std::nullopt;
    const std::size_t i = size();
    resize(i + 1);
    return Traits::ref(seq_->_buffer[i]);
  }

 private:
  Sequence* seq_;
};

// Points a sequence at `storage` of Bound elements, empty (for the generated owning types).
template <class Sequence, class Stored, std::size_t Bound>
void bind_sequence(Sequence& seq, Stored (&storage)[Bound]) noexcept {
  seq._maximum = static_cast<std::uint32_t>(Bound);
  seq._length = 0;
  seq._buffer = storage;
  seq._release = false;  // ours: Cyclone must never free it
}

// Copies the elements of `from` (at most Bound) into `storage` and points `seq` at them.
template <class Sequence, class Stored, std::size_t Bound>
void copy_sequence(Sequence& seq, Stored (&storage)[Bound], const Sequence& from) noexcept {
  bind_sequence(seq, storage);
  const std::size_t n = from._buffer == nullptr ? 0 : std::min<std::size_t>(from._length, Bound);
  if (n > 0 && from._buffer != storage) std::memmove(storage, from._buffer, n * sizeof(Stored));
  seq._length = static_cast<std::uint32_t>(n);
}

// WireOf<T>::type: the idlc C struct behind a generated typed class (its `Wire`), or T itself.
template <class T>
struct WireOf {
  using type = T;
};
template <class T>
requires requires {
  typename T::Wire;
}
struct WireOf<T> {
  using type = typename T::Wire;
};
template <class T>
using wire_t = typename WireOf<T>::type;

}  // namespace hubrt::msgs::typed
