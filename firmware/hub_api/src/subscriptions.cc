#include "hubrt/hub_api/subscriptions.h"

#include <string>
#include <vector>

#include <fmt/ranges.h>

#include "hubrt/msgs/all_types.h"

namespace hubrt::hub_api {
namespace {

class SubscriptionStage final : public runtime::CycleStage {
 public:
  struct Source {
    RemoteStateBase* state;
    dds::UntypedReader* reader;
  };
  explicit SubscriptionStage(std::vector<Source> sources) : sources_(std::move(sources)) {}

  void before_nodes(const Instant& now) noexcept override {
    for (const Source& source : sources_) {
      // Latest wins; bounded so that a flood cannot stall the cycle.
      for (int i = 0; i < 32; ++i) {
        const Result<bool> taken = source.reader->take_next(source.state->sample_data());
        if (!taken.is_ok() || !taken.value()) break;
        source.state->note_arrival(now.mono);
      }
    }
  }
  void after_nodes(const Instant& /*now*/, bool /*publish_all*/, bool /*took_effect*/) noexcept override {}

 private:
  std::vector<Source> sources_;
};

}  // namespace

Expected<Subscriptions::Found> Subscriptions::find(const config::HubConfig& config, std::string_view name,
                                                   const msgs::TypeInfo& expected) {
  const config::Subscription* sub = nullptr;
  for (const auto& s : config.subscriptions) {
    if (s.name == name) sub = &s;
  }
  if (sub == nullptr) {
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("{}: this hub needs the State of another hub as input '{}' ({}); add it under "
                    "subscriptions: with its topic and type",
                    config.file, name, expected.ros_name));
  }
  // The types this program holds: a board's program only those its hub types link (hubs/HubTypes.cmake).
  const msgs::TypeRegistry& types = msgs::all_types();
  const msgs::TypeInfo* type = types.find(sub->type);
  if (type == nullptr || type->descriptor == nullptr) {
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("{}: subscriptions.{}.type: {} (this hubd holds the message types of its hub "
                    "types and their inputs)",
                    config.file, name, types.unknown_type_message(sub->type)));
  }
  Found found{sub->name, sub->topic, sub->timeout, type->descriptor, 0};
  if (sub->field.empty()) {
    if (type != &expected) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: subscriptions.{}: input '{}' must be a {}, not {}", config.file,
                                    name, name, expected.ros_name, type->ros_name));
    }
    return found;
  }
  for (const msgs::FieldInfo& field : type->fields) {
    if (field.name == sub->field && field.kind == msgs::FieldKind::kStruct && field.nested == &expected) {
      found.field_offset = field.offset;
      return found;
    }
  }
  return make_error(ErrorCode::kInvalidArgument,
                    fmt::format("{}: subscriptions.{}.field: {} has no field '{}' of type {}", config.file,
                                name, type->ros_name, sub->field, expected.ros_name));
}

Expected<void> Subscriptions::add(std::unique_ptr<RemoteStateBase> state, const Found& found) {
  auto entry = std::make_unique<Entry>();
  auto topic = dds::UntypedTopic::create(participant_, *found.descriptor, found.topic);
  if (!topic) return std::move(topic).error();
  entry->topic.emplace(std::move(*topic));
  auto reader = dds::UntypedReader::create(participant_, *entry->topic);
  if (!reader) return std::move(reader).error();
  entry->reader.emplace(std::move(*reader));
  entry->state = std::move(state);
  entries_.push_back(std::move(entry));
  return {};
}

std::unique_ptr<runtime::CycleStage> Subscriptions::make_stage() {
  if (entries_.empty()) return nullptr;
  std::vector<SubscriptionStage::Source> sources;
  for (const auto& entry : entries_) sources.push_back({entry->state.get(), &*entry->reader});
  return std::make_unique<SubscriptionStage>(std::move(sources));
}

}  // namespace hubrt::hub_api
