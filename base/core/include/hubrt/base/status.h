// Error handling without exceptions, in two weights:
//   Status / Result<T>  — a code only; used on the cycle path, never allocates.
//   Error / Expected<T> — a code and a human message; used when opening devices and loading
//                         configuration, where saying *why* matters more than allocation.
#pragma once

#include <cassert>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace hubrt {

enum class ErrorCode : std::uint8_t {
  kOk = 0,
  kInvalidArgument,     // the caller passed something malformed or out of range
  kNotFound,            // a device, file, chip, line or interface does not exist
  kPermissionDenied,    // it exists but we may not use it
  kBusy,                // held by someone else
  kTimeout,             // no answer within the allotted time
  kIo,                  // the device answered with an error or the transfer failed
  kUnavailable,         // not (or no longer) reachable: link down, server gone, bus off
  kProtocol,            // the peer answered something we do not understand
  kOutOfRange,          // a value outside its allowed range
  kFailedPrecondition,  // refused because of the current state (interlock, not open)
  kInternal,            // a bug on our side
};

// Stable lower-case name of a code, e.g. "timeout".
std::string_view to_string(ErrorCode code) noexcept;

// A code only. Cheap to copy, never allocates.
class [[nodiscard]] Status {
 public:
  constexpr Status() noexcept = default;
  constexpr explicit Status(ErrorCode code) noexcept : code_(code) {}

  static constexpr Status ok() noexcept { return Status(); }
  [[nodiscard]] constexpr bool is_ok() const noexcept { return code_ == ErrorCode::kOk; }
  [[nodiscard]] constexpr ErrorCode code() const noexcept { return code_; }
  // Explicitly discards a status whose failure is handled elsewhere.
  constexpr void ignore() const noexcept {}

  friend constexpr bool operator==(Status a, Status b) noexcept { return a.code_ == b.code_; }

 private:
  ErrorCode code_ = ErrorCode::kOk;
};

// A value or a non-ok Status. Never allocates beyond what T does.
template <class T>
class [[nodiscard]] Result {
 public:
  // NOLINTNEXTLINE(google-explicit-constructor): implicit on purpose, as with std::optional.
  constexpr Result(T value) noexcept(std::is_nothrow_move_constructible_v<T>) : value_(std::move(value)) {}
  // NOLINTNEXTLINE(google-explicit-constructor)
  constexpr Result(Status status) noexcept : status_(status) { assert(!status.is_ok()); }

  [[nodiscard]] constexpr bool is_ok() const noexcept { return status_.is_ok(); }
  [[nodiscard]] constexpr Status status() const noexcept { return status_; }
  // Precondition: is_ok().
  constexpr const T& value() const& noexcept { return value_; }
  constexpr T& value() & noexcept { return value_; }
  constexpr T value_or(T fallback) const noexcept { return is_ok() ? value_ : fallback; }

 private:
  T value_{};
  Status status_;
};

// A code plus a message that names what failed and why (e.g. the file and line, the device path).
struct Error {
  ErrorCode code = ErrorCode::kInternal;
  std::string message;
};

// A value or an Error. Used by factories and loaders, not in the cycle.
template <class T>
class [[nodiscard]] Expected {
 public:
  // NOLINTNEXTLINE(google-explicit-constructor)
  Expected(T value) : storage_(std::in_place_index<0>, std::move(value)) {}
  // NOLINTNEXTLINE(google-explicit-constructor)
  Expected(Error error) : storage_(std::in_place_index<1>, std::move(error)) {}

  [[nodiscard]] bool is_ok() const noexcept { return storage_.index() == 0; }
  explicit operator bool() const noexcept { return is_ok(); }
  // Precondition: is_ok().
  T& value() & { return std::get<0>(storage_); }
  const T& value() const& { return std::get<0>(storage_); }
  T&& value() && { return std::get<0>(std::move(storage_)); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T&& operator*() && { return std::move(*this).value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  // Precondition: !is_ok().
  [[nodiscard]] const Error& error() const& { return std::get<1>(storage_); }
  Error&& error() && { return std::get<1>(std::move(storage_)); }

 private:
  std::variant<T, Error> storage_;
};

// Expected<void>: success or an Error.
template <>
class [[nodiscard]] Expected<void> {
 public:
  Expected() = default;
  // NOLINTNEXTLINE(google-explicit-constructor)
  Expected(Error error) : error_(std::move(error)), ok_(false) {}

  [[nodiscard]] bool is_ok() const noexcept { return ok_; }
  explicit operator bool() const noexcept { return ok_; }
  [[nodiscard]] const Error& error() const& { return error_; }
  Error&& error() && { return std::move(error_); }

 private:
  Error error_;
  bool ok_ = true;
};

inline Error make_error(ErrorCode code, std::string message) {
  return Error{code, std::move(message)};
}

}  // namespace hubrt
