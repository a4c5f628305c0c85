#include "operator_hub_hub_type.h"

#include <fmt/format.h>

#include "hubrt/hub_api/hub_layout.h"
#include "hubrt/hub_api/subscriptions.h"
#include "hubrt/hubs/board_devices.h"

#include "operator_panel_logic.h"
#include "operator_settings.h"

namespace hubrt::operator_hub {
namespace {

// The reader of the board, opened now (not open: handed in anyway and retried by the node).
Expected<hal::SupervisedBadgeReader> open_board_reader(const hal::BoardConfig& board, hal::Backend& backend,
                                                       std::string_view owner, std::string_view reader,
                                                       Time now) {
  const hal::BoardBadgeReader* found = board.find_badge_reader(reader);
  if (found == nullptr) {
    return make_error(ErrorCode::kNotFound,
                      fmt::format("{}: board {} has no RFID reader '{}'", owner, board.file, reader));
  }
  hal::SupervisedBadgeReader opened(backend, found->config);
  opened.open_now(now);
  return opened;
}

class OperatorHubType final : public hub_api::HubType {
 public:
  [[nodiscard]] std::string_view name() const noexcept override { return OperatorHubTypes::kType; }

  [[nodiscard]] Expected<hal::BoardRequirements> requirements(
      const config::HubConfig& config) const override {
    hal::BoardRequirements required;
    required.hub = config.type;
    for (const config::NodeConfig& node : config.nodes) {
      if (node.type != OperatorPanelLogic::kType) {
        return node.settings.error_at("type",
                                      fmt::format("an operator_hub hub has nodes of type '{}' only, not '{}'",
                                                  OperatorPanelLogic::kType, node.type));
      }
      auto settings = parse_operator_settings(node, config.file);
      if (!settings) return std::move(settings).error();
      add_requirements(*settings, required);
    }
    return required;
  }

  // The allow-list is loaded here too, so that `hubd --check` finds its mistakes (file:line).
  [[nodiscard]] Expected<void> check(const config::HubConfig& config) const override {
    for (const config::NodeConfig& node : config.nodes) {
      auto settings = parse_operator_settings(node, config.file);
      if (!settings) return std::move(settings).error();
      if (!settings->screen_confirm.empty()) {
        auto screen =
            hub_api::Subscriptions::check<hub_msgs::OperatorConfirmView>(config, settings->screen_confirm);
        if (!screen) return screen;
      }
      auto list = AllowList::load(settings->allow_list);
      if (!list) return std::move(list).error();
      auto wired = hub_api::NodeWiring<OperatorHubTypes>::check<OperatorPanelLogic>(config, node);
      if (!wired) return wired;
    }
    return {};
  }

  [[nodiscard]] Expected<void> build(const hub_api::HubContext& context, runtime::Hub& hub) const override {
    auto wiring = hub_api::NodeWiring<OperatorHubTypes>::create(context, hub);
    if (!wiring) return std::move(wiring).error();
    const Time now = context.clock.now().mono;
    for (const config::NodeConfig& node : context.config.nodes) {
      auto settings = parse_operator_settings(node, context.config.file);
      if (!settings) return std::move(settings).error();
      auto list = AllowList::load(settings->allow_list);
      if (!list) return std::move(list).error();
      const ScreenConfirmInput* screen = nullptr;
      if (!settings->screen_confirm.empty()) {
        auto subscribed = context.subscriptions.get<hub_msgs::OperatorConfirmView>(settings->screen_confirm);
        if (!subscribed) return std::move(subscribed).error();
        screen = *subscribed;
      }
      const std::string owner = fmt::format("operator panel '{}'", node.name);
      auto reader = open_board_reader(context.board, context.backend, owner, settings->reader, now);
      if (!reader) return std::move(reader).error();
      OperatorDevices devices{std::move(*reader), std::nullopt};
      if (!settings->confirm_button.empty()) {
        auto button =
            hubs::open_board_input(context.board, context.backend, owner, settings->confirm_button, now);
        if (!button) return std::move(button).error();
        devices.button.emplace(std::move(*button));
      }
      auto logic = OperatorPanelLogic::create(std::move(*list), std::move(devices), screen, now);
      if (!logic) return std::move(logic).error();
      auto added = wiring->add(node, std::move(*logic));
      if (!added) return added;
    }
    return wiring->finish();
  }
};

}  // namespace

const hub_api::HubType& operator_hub_hub_type() noexcept {
  static const OperatorHubType type;
  return type;
}

}  // namespace hubrt::operator_hub
