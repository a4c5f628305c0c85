#include "signal_lamp_hub_type.h"

#include <fmt/format.h>

#include "hubrt/hub_api/hub_layout.h"
#include "hubrt/hubs/board_devices.h"

#include "lamp_logic.h"

namespace hubrt::signal_lamp {
namespace {

class SignalLampHubType final : public hub_api::HubType {
 public:
  [[nodiscard]] std::string_view name() const noexcept override { return SignalLampTypes::kType; }

  // Reads every node's settings (errors name file:line) and lists the board outputs they use;
  // hubd checks them against the board before anything is opened.
  [[nodiscard]] Expected<hal::BoardRequirements> requirements(
      const config::HubConfig& config) const override {
    hal::BoardRequirements required;
    required.hub = config.type;
    for (const config::NodeConfig& node : config.nodes) {
      if (node.type != LampLogic::kType) {
        return node.settings.error_at(
            "type", fmt::format("a signal_lamp hub has nodes of type '{}' only, not '{}'", LampLogic::kType,
                                node.type));
      }
      auto signal = parse_lamp_signal(node);
      if (!signal) return std::move(signal).error();
      add_requirements(*signal, required);
    }
    return required;
  }

  // What build() would refuse that the configuration alone shows (the hub layout's fields).
  [[nodiscard]] Expected<void> check(const config::HubConfig& config) const override {
    for (const config::NodeConfig& node : config.nodes) {
      auto wired = hub_api::NodeWiring<SignalLampTypes>::check<LampLogic>(config, node);
      if (!wired) return wired;
    }
    return {};
  }

  // Opens each lamp's output from the board (a line that fails to open is handed in not open and
  // retried by the node) and wires the node in the configured layout.
  [[nodiscard]] Expected<void> build(const hub_api::HubContext& context, runtime::Hub& hub) const override {
    auto wiring = hub_api::NodeWiring<SignalLampTypes>::create(context, hub);
    if (!wiring) return std::move(wiring).error();
    const Time now = context.clock.now().mono;
    for (const config::NodeConfig& node : context.config.nodes) {
      auto signal = parse_lamp_signal(node);
      if (!signal) return std::move(signal).error();
      auto output = hubs::open_board_output(context.board, context.backend,
                                            fmt::format("lamp '{}'", node.name), *signal, now);
      if (!output) return std::move(output).error();
      auto added = wiring->add(node, LampLogic(std::move(*output)));
      if (!added) return added;
    }
    return wiring->finish();
  }
};

}  // namespace

const hub_api::HubType& signal_lamp_hub_type() noexcept {
  static const SignalLampHubType type;
  return type;
}

}  // namespace hubrt::signal_lamp
