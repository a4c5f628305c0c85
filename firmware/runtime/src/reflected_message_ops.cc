#include "hubrt/runtime/reflected_message_ops.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "hubrt/base/utf8.h"
#include "hubrt/runtime/escaped_text.h"

namespace hubrt::runtime {
namespace {

constexpr const char* kNotUtf8 = "is not valid UTF-8";
constexpr const char* kControlCharacter = "contains a control character";

using msgs::FieldInfo;
using msgs::FieldKind;
using msgs::TypeInfo;

// The layout idlc gives every dds_sequence_X.
struct AnySequence {
  std::uint32_t _maximum;
  std::uint32_t _length;
  void* _buffer;
  bool _release;
};

const std::byte* at(const void* base, std::size_t offset) noexcept {
  return static_cast<const std::byte*>(base) + offset;
}
std::byte* at(void* base, std::size_t offset) noexcept {
  return static_cast<std::byte*>(base) + offset;
}

bool struct_equal(const TypeInfo& type, const void* a, const void* b) noexcept;
bool struct_copy(const TypeInfo& type, const void* src, void* dst, Arena& arena) noexcept;

bool element_equal(const FieldInfo& field, const void* a, const void* b) noexcept {
  switch (field.element_kind) {
    case FieldKind::kString: {
      if (field.string_bound != 0) return msgs::string_at(field, a) == msgs::string_at(field, b);
      const char* x = *static_cast<const char* const*>(a);
      const char* y = *static_cast<const char* const*>(b);
      if (x == nullptr || y == nullptr) return x == y;
      return std::strcmp(x, y) == 0;
    }
    case FieldKind::kStruct:
      return struct_equal(*field.nested, a, b);
    case FieldKind::kFloat32: {  // by value, so that 0.0 == -0.0 like the planner would expect
      float x = 0;
      float y = 0;
      std::memcpy(&x, a, sizeof x);
      std::memcpy(&y, b, sizeof y);
      return x == y;
    }
    case FieldKind::kFloat64: {
      double x = 0;
      double y = 0;
      std::memcpy(&x, a, sizeof x);
      std::memcpy(&y, b, sizeof y);
      return x == y;
    }
    default:
      return std::memcmp(a, b, field.element_size) == 0;
  }
}

bool elements_equal(const FieldInfo& field, const void* a, const void* b, std::uint32_t count) noexcept {
  for (std::uint32_t i = 0; i < count; ++i) {
    if (!element_equal(field, at(a, i * field.element_size), at(b, i * field.element_size))) return false;
  }
  return true;
}

bool struct_equal(const TypeInfo& type, const void* a, const void* b) noexcept {
  for (const FieldInfo& field : type.fields) {
    const void* fa = at(a, field.offset);
    const void* fb = at(b, field.offset);
    if (field.kind == FieldKind::kSequence) {
      const auto* sa = static_cast<const AnySequence*>(fa);
      const auto* sb = static_cast<const AnySequence*>(fb);
      if (sa->_length != sb->_length) return false;
      if (sa->_length > 0 && !elements_equal(field, sa->_buffer, sb->_buffer, sa->_length)) return false;
    } else if (field.kind == FieldKind::kArray) {
      if (!elements_equal(field, fa, fb, field.bound)) return false;
    } else if (!element_equal(field, fa, fb)) {
      return false;
    }
  }
  return true;
}

bool copy_string(const char* src, char** dst, Arena& arena) noexcept {
  if (src == nullptr) {
    *dst = nullptr;
    return true;
  }
  const std::size_t n = std::strlen(src) + 1;
  auto* copy = static_cast<char*>(arena.allocate(n, 1));
  if (copy == nullptr) return false;
  std::memcpy(copy, src, n);
  *dst = copy;
  return true;
}

bool copy_element(const FieldInfo& field, const void* src, void* dst, Arena& arena) noexcept {
  switch (field.element_kind) {
    case FieldKind::kString:
      if (field.string_bound != 0) {  // inline char[N+1]
        std::memcpy(dst, src, field.element_size);
        return true;
      }
      return copy_string(*static_cast<const char* const*>(src), static_cast<char**>(dst), arena);
    case FieldKind::kStruct:
      return struct_copy(*field.nested, src, dst, arena);
    default:
      std::memcpy(dst, src, field.element_size);
      return true;
  }
}

bool copy_elements(const FieldInfo& field, const void* src, void* dst, std::uint32_t count,
                   Arena& arena) noexcept {
  for (std::uint32_t i = 0; i < count; ++i) {
    if (!copy_element(field, at(src, i * field.element_size), at(dst, i * field.element_size), arena))
      return false;
  }
  return true;
}

bool struct_copy(const TypeInfo& type, const void* src, void* dst, Arena& arena) noexcept {
  for (const FieldInfo& field : type.fields) {
    const void* from = at(src, field.offset);
    void* to = at(dst, field.offset);
    if (field.kind == FieldKind::kSequence) {
      const auto* s = static_cast<const AnySequence*>(from);
      auto* d = static_cast<AnySequence*>(to);
      d->_maximum = s->_length;
      d->_length = s->_length;
      d->_release = false;  // arena storage: never freed by Cyclone
      d->_buffer = nullptr;
      if (s->_length == 0) continue;
      d->_buffer = arena.allocate(std::size_t{s->_length} * field.element_size, alignof(std::max_align_t));
      if (d->_buffer == nullptr) return false;
      std::memset(d->_buffer, 0, std::size_t{s->_length} * field.element_size);
      if (!copy_elements(field, s->_buffer, d->_buffer, s->_length, arena)) return false;
    } else if (field.kind == FieldKind::kArray) {
      if (!copy_elements(field, from, to, field.bound, arena)) return false;
    } else if (!copy_element(field, from, to, arena)) {
      return false;
    }
  }
  return true;
}

// Depth-first walk over every string and float, with the dotted path of the field for the message.
class FieldChecker {
 public:
  FieldChecker(std::size_t max_length, Problem& problem) noexcept
      : max_length_(max_length), problem_(problem) {}

  bool check_struct(const TypeInfo& type, const void* msg) noexcept {
    for (const FieldInfo& field : type.fields) {
      const std::size_t mark = push(field.name);
      const void* value = at(msg, field.offset);
      bool ok = true;
      if (field.kind == FieldKind::kSequence) {
        const auto* seq = static_cast<const AnySequence*>(value);
        ok = check_elements(field, seq->_buffer, seq->_length);
      } else if (field.kind == FieldKind::kArray) {
        ok = check_elements(field, value, field.bound);
      } else {
        ok = check_element(field, value);
      }
      if (!ok) return false;
      path_length_ = mark;
    }
    return true;
  }

 private:
  bool check_elements(const FieldInfo& field, const void* first, std::uint32_t count) noexcept {
    if (!needs_check(field.element_kind)) return true;
    const std::size_t mark = path_length_;
    for (std::uint32_t i = 0; i < count; ++i) {
      append_index(i);
      if (!check_element(field, at(first, i * field.element_size))) return false;
      path_length_ = mark;
    }
    return true;
  }

  bool check_element(const FieldInfo& field, const void* value) noexcept {
    if (field.element_kind == FieldKind::kStruct) return check_struct(*field.nested, value);
    if (field.element_kind == FieldKind::kFloat32 || field.element_kind == FieldKind::kFloat64) {
      double number = 0;
      if (field.element_kind == FieldKind::kFloat32) {
        float f = 0;
        std::memcpy(&f, value, sizeof f);
        number = f;
      } else {
        std::memcpy(&number, value, sizeof number);
      }
      if (std::isfinite(number)) return true;
      problem_.format("field '{}' is not a finite number ({})", std::string_view(path_.data(), path_length_),
                      number);
      return false;
    }
    if (field.element_kind != FieldKind::kString) return true;
    // A bounded string (char[N+1]) is read up to its NUL; without one it reads as N+1 bytes, too
    // long for any limit of N or less.
    const std::string_view whole = msgs::string_at(field, value);
    const char* why = field.string_bound != 0
                          ? string_problem(whole, max_length_)
                          : string_problem(*static_cast<const char* const*>(value), max_length_);
    if (why == nullptr) return true;
    const std::string_view path(path_.data(), path_length_);
    if (why == kNotUtf8 || why == kControlCharacter) {
      // Quoted escaped, so that the operator sees which bytes came and the State stays UTF-8.
      problem_.format("field '{}' {}: '{}' (limit {} bytes of UTF-8 text)", path, why,
                      Escaped{whole.substr(0, max_length_)}, max_length_);
    } else {
      problem_.format("field '{}' {} (limit {} bytes of UTF-8 text)", path, why, max_length_);
    }
    return false;
  }

  static bool needs_check(FieldKind kind) noexcept {
    return kind == FieldKind::kString || kind == FieldKind::kStruct || kind == FieldKind::kFloat32 ||
           kind == FieldKind::kFloat64;
  }

  std::size_t push(std::string_view name) noexcept {
    const std::size_t mark = path_length_;
    if (path_length_ > 0) append(".");
    append(name);
    return mark;
  }
  void append_index(std::uint32_t i) noexcept {
    std::array<char, 16> digits{};
    const auto r = fmt::format_to_n(digits.data(), digits.size(), "[{}]", i);
    append(std::string_view(digits.data(), r.size));
  }
  void append(std::string_view text) noexcept {
    const std::size_t n = std::min(text.size(), path_.size() - path_length_);
    text.copy(path_.data() + path_length_, n);
    path_length_ += n;
  }

  std::size_t max_length_;
  Problem& problem_;
  std::array<char, 96> path_{};
  std::size_t path_length_ = 0;
};

}  // namespace

const char* string_problem(const char* text, std::size_t max_length) noexcept {
  if (text == nullptr) return "is missing";
  // strnlen: never reads further than one byte past the limit, however long the string.
  return string_problem(std::string_view(text, strnlen(text, max_length + 1)), max_length);
}

const char* string_problem(std::string_view bytes, std::size_t max_length) noexcept {
  if (bytes.size() > max_length) return "is too long";
  if (!is_valid_utf8(bytes)) return kNotUtf8;
  for (const char c : bytes) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return kControlCharacter;
  }
  return nullptr;
}

bool ReflectedMessageOps::equal(const void* a, const void* b) const noexcept {
  return struct_equal(type_, a, b);
}

bool ReflectedMessageOps::copy_into(const void* src, void* dst, Arena& arena) const noexcept {
  arena.reset();
  std::memset(dst, 0, type_.size);
  if (struct_copy(type_, src, dst, arena)) return true;
  std::memset(dst, 0, type_.size);
  return false;
}

bool ReflectedMessageOps::check_fields(const void* msg, std::size_t max_length,
                                       Problem& problem) const noexcept {
  FieldChecker checker(max_length, problem);
  return checker.check_struct(type_, msg);
}

}  // namespace hubrt::runtime
