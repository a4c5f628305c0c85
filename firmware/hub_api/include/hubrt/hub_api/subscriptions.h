// The hub's subscriptions to other hubs' States: made when a node asks for one by name, read
// every cycle before the nodes step (a CycleStage), handed to the logic as RemoteState<T>.
#pragma once

#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "hubrt/base/status.h"
#include "hubrt/config/hub_config.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/hub_api/remote_state.h"
#include "hubrt/msgs/type_info.h"
#include "hubrt/runtime/hub.h"

namespace hubrt::hub_api {

class Subscriptions {
 public:
  Subscriptions(const config::HubConfig& config, const dds::Participant& participant)
      : config_(config), participant_(participant) {}

  // The subscription `name` of the hub file, as a State of type T (the field `field:` of the
  // received type when the hub file gives one). Errors (file and line): no such subscription,
  // its type unknown, or not T (nor holding a T in `field:`); DDS entities that fail.
  template <class T>
  Expected<RemoteState<T>*> get(std::string_view name) {
    auto found = prepare(name, msgs::type_info_of<msgs::typed::wire_t<T>>());
    if (!found) return std::move(found).error();
    auto state = std::make_unique<RemoteState<T>>(found->name, found->topic, found->timeout,
                                                  *found->descriptor, found->field_offset);
    RemoteState<T>* typed = state.get();
    if (auto ok = add(std::move(state), *found); !ok) return std::move(ok).error();
    return typed;
  }

  // What get<T>(name) checks in the configuration alone — the subscription exists, its type is
  // T or holds a T in `field:` — without DDS (`hubd --check`). Errors: as get().
  template <class T>
  static Expected<void> check(const config::HubConfig& config, std::string_view name) {
    auto found = find(config, name, msgs::type_info_of<msgs::typed::wire_t<T>>());
    if (!found) return std::move(found).error();
    return {};
  }

  // A CycleStage that takes the received States before the nodes step. Add it to the hub after
  // the nodes asked for their subscriptions; nullptr when there are none.
  std::unique_ptr<runtime::CycleStage> make_stage();

 private:
  struct Found {
    std::string name;
    std::string topic;
    Duration timeout{};
    const dds_topic_descriptor_t* descriptor = nullptr;
    std::size_t field_offset = 0;
  };
  struct Entry {
    std::unique_ptr<RemoteStateBase> state;
    std::optional<dds::UntypedTopic> topic;
    std::optional<dds::UntypedReader> reader;
  };

  static Expected<Found> find(const config::HubConfig& config, std::string_view name,
                              const msgs::TypeInfo& expected);
  Expected<Found> prepare(std::string_view name, const msgs::TypeInfo& expected) const {
    return find(config_, name, expected);
  }
  Expected<void> add(std::unique_ptr<RemoteStateBase> state, const Found& found);

  const config::HubConfig& config_;
  const dds::Participant& participant_;
  std::vector<std::unique_ptr<Entry>> entries_;  // heap-held: the stage points into them
};

}  // namespace hubrt::hub_api
