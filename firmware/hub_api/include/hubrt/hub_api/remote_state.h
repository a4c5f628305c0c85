// Another hub's State, consumed as an input through the hub file's `subscriptions:` — e.g. the
// Tool ECU watching whether the RSP ECU holds the smart tool. Generic: any State type, from a
// node's own topic or embedded in a hub-layout State (`field:`).
//
// A State that never arrived, or arrived longer ago than the subscription's timeout, is *lost*:
// fresh() returns nullptr, and logic that depends on it must treat that as "not allowed".
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <type_traits>

#include "hubrt/base/time.h"
#include "hubrt/dds/sample.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/runtime/text_buffer.h"

namespace hubrt::hub_api {

// The type-independent part, filled by SubscriptionStage on the cycle thread.
class RemoteStateBase {
 public:
  RemoteStateBase(std::string name, std::string topic, Duration timeout,
                  const dds_topic_descriptor_t& descriptor, std::size_t field_offset)
      : name_(std::move(name)),
        topic_(std::move(topic)),
        timeout_(timeout),
        sample_(descriptor),
        field_offset_(field_offset) {}

  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  [[nodiscard]] const std::string& topic() const noexcept { return topic_; }
  [[nodiscard]] Duration timeout() const noexcept { return timeout_; }
  [[nodiscard]] bool ever_received() const noexcept { return received_ > 0; }
  [[nodiscard]] std::uint64_t received() const noexcept { return received_; }
  [[nodiscard]] bool is_fresh(Time now) const noexcept {
    return received_ > 0 && now - last_arrival_ <= timeout_;
  }
  // Why the State is lost, for an error_list entry; empty while fresh. Allocation-free.
  [[nodiscard]] std::string_view loss_reason(Time now) noexcept;

  // For SubscriptionStage: the sample to take into, and the arrival time of what it took.
  [[nodiscard]] void* sample_data() noexcept { return sample_.data(); }
  void note_arrival(Time now) noexcept {
    last_arrival_ = now;
    ++received_;
  }

 protected:
  [[nodiscard]] const void* field() const noexcept {
    return static_cast<const std::byte*>(sample_.data()) + field_offset_;
  }

 private:
  std::string name_;
  std::string topic_;
  Duration timeout_;
  dds::UntypedSample sample_;
  std::size_t field_offset_;
  Time last_arrival_{};
  std::uint64_t received_ = 0;
  runtime::TextBuffer<160> reason_;
};

// Typed view: T is the State type the logic expects (checked when the subscription is made):
// a generated View (e.g. hub_msgs::DockStateView) or an idlc C struct.
template <class T>
class RemoteState final : public RemoteStateBase {
 public:
  using Wire = msgs::typed::wire_t<T>;
  using RemoteStateBase::RemoteStateBase;
  // The latest State if it is fresh at `now`: a View (std::nullopt when not fresh) or, for a C
  // struct, a pointer (nullptr when not fresh). Valid until the next cycle.
  [[nodiscard]] auto fresh(Time now) const noexcept {
    if constexpr (std::is_same_v<T, Wire>) {
      return is_fresh(now) ? static_cast<const T*>(field()) : nullptr;
    } else {
      return is_fresh(now) ? std::optional<T>(T(*static_cast<const Wire*>(field()))) : std::nullopt;
    }
  }
};

}  // namespace hubrt::hub_api
