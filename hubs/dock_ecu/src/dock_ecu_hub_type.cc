#include "dock_ecu_hub_type.h"

#include <fmt/format.h>

#include "hubrt/hub_api/hub_layout.h"
#include "hubrt/hubs/board_devices.h"

#include "dock_logic.h"

namespace hubrt::dock_ecu {

Expected<std::vector<hal::SupervisedInput>> open_slot_sensors(const std::vector<SlotConfig>& slots,
                                                              const hal::BoardConfig& board,
                                                              hal::Backend& backend, Time now) {
  std::vector<hal::SupervisedInput> sensors;
  sensors.reserve(slots.size());
  for (const SlotConfig& slot : slots) {
    auto sensor =
        hubs::open_board_input(board, backend, fmt::format("slot '{}'", slot.name), slot.signal, now);
    if (!sensor) return std::move(sensor).error();
    sensors.push_back(std::move(*sensor));
  }
  return sensors;
}

namespace {

class DockEcuHubType final : public hub_api::HubType {
 public:
  [[nodiscard]] std::string_view name() const noexcept override { return "dock_ecu"; }

  [[nodiscard]] Expected<hal::BoardRequirements> requirements(
      const config::HubConfig& config) const override {
    hal::BoardRequirements required;
    required.hub = config.type;
    for (const config::NodeConfig& node : config.nodes) {
      if (node.type != DockLogic::kType) {
        return node.settings.error_at(
            "type",
            fmt::format("a dock_ecu hub has nodes of type '{}' only, not '{}'", DockLogic::kType, node.type));
      }
      auto slots = parse_slots(node);
      if (!slots) return std::move(slots).error();
      add_requirements(*slots, required);
    }
    return required;
  }

  [[nodiscard]] Expected<void> check(const config::HubConfig& config) const override {
    for (const config::NodeConfig& node : config.nodes) {
      auto wired = hub_api::NodeWiring<DockEcuTypes>::check<DockLogic>(config, node);
      if (!wired) return wired;
    }
    return {};
  }

  [[nodiscard]] Expected<void> build(const hub_api::HubContext& context, runtime::Hub& hub) const override {
    auto wiring = hub_api::NodeWiring<DockEcuTypes>::create(context, hub);
    if (!wiring) return std::move(wiring).error();
    const Time now = context.clock.now().mono;
    for (const config::NodeConfig& node : context.config.nodes) {
      auto slots = parse_slots(node);
      if (!slots) return std::move(slots).error();
      auto sensors = open_slot_sensors(*slots, context.board, context.backend, now);
      if (!sensors) return std::move(sensors).error();
      auto logic = DockLogic::create(*slots, std::move(*sensors));
      if (!logic) return std::move(logic).error();
      auto added = wiring->add(node, std::move(*logic));
      if (!added) return added;
    }
    return wiring->finish();
  }
};

}  // namespace

const hub_api::HubType& dock_ecu_hub_type() noexcept {
  static const DockEcuHubType type;
  return type;
}

}  // namespace hubrt::dock_ecu
