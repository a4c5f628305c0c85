#include "mir_com_hub_type.h"

#include <fmt/format.h>

#include "hubrt/hal/common/threaded_async_http.h"
#include "hubrt/hub_api/hub_layout.h"

#include "pose_saver_logic.h"
#include "robot_mover_logic.h"

namespace hubrt::mir_com {

namespace {

Error in_node(const config::NodeConfig& node, const Error& error) {
  return make_error(error.code, fmt::format("node '{}': {}", node.name, error.message));
}

// The platform's HTTP client from the board (its authorization read now, not at --check), behind
// the HAL's worker thread with the MiR decoder: the logic submits and polls.
// Errors: the device missing from the board (kNotFound), the authorization file, the backend's.
Expected<std::unique_ptr<MirDevice>> open_platform(const MirLinkSettings& settings,
                                                   const hal::BoardConfig& board, hal::Backend& backend) {
  const hal::BoardHttpDevice* device = board.find_http(settings.device);
  if (device == nullptr) {
    return make_error(ErrorCode::kNotFound,
                      fmt::format("board {} has no HTTP device '{}'", board.file, settings.device));
  }
  hal::HttpConfig config = device->config;
  auto authorization = hal::load_http_authorization(*device);
  if (!authorization) return std::move(authorization).error();
  config.authorization = std::move(*authorization);
  auto client = backend.open_http(config);
  if (!client) return std::move(client).error();
  return hal::open_threaded_async_http<protocol::mir::MirReply>(
      std::move(*client), protocol::mir::decode_reply, hal::http_request_timeout(config),
      hal::describe_http(config));
}

class MirComHubType final : public hub_api::HubType {
 public:
  [[nodiscard]] std::string_view name() const noexcept override { return MirComTypes::kType; }

  [[nodiscard]] Expected<hal::BoardRequirements> requirements(
      const config::HubConfig& config) const override {
    hal::BoardRequirements required;
    required.hub = config.type;
    for (const config::NodeConfig& node : config.nodes) {
      if (node.type == RobotMoverLogic::kType) {
        auto settings = parse_robot_mover_settings(node);
        if (!settings) return std::move(settings).error();
        add_requirements(settings->link, required);
      } else if (node.type == PoseSaverLogic::kType) {
        auto settings = parse_pose_saver_settings(node);
        if (!settings) return std::move(settings).error();
        add_requirements(settings->link, required);
      } else {
        return node.settings.error_at("type",
                                      fmt::format("a mir_com hub has nodes of type '{}' or '{}', not '{}'",
                                                  RobotMoverLogic::kType, PoseSaverLogic::kType, node.type));
      }
    }
    return required;
  }

  [[nodiscard]] Expected<void> check(const config::HubConfig& config) const override {
    for (const config::NodeConfig& node : config.nodes) {
      auto wired = node.type == RobotMoverLogic::kType
                       ? hub_api::NodeWiring<MirComTypes>::check<RobotMoverLogic>(config, node)
                       : hub_api::NodeWiring<MirComTypes>::check<PoseSaverLogic>(config, node);
      if (!wired) return wired;
    }
    return {};
  }

  [[nodiscard]] Expected<void> build(const hub_api::HubContext& context, runtime::Hub& hub) const override {
    auto wiring = hub_api::NodeWiring<MirComTypes>::create(context, hub);
    if (!wiring) return std::move(wiring).error();
    for (const config::NodeConfig& node : context.config.nodes) {
      Expected<void> added;
      if (node.type == RobotMoverLogic::kType) {
        auto settings = parse_robot_mover_settings(node);
        if (!settings) return std::move(settings).error();
        auto device = open_platform(settings->link, context.board, context.backend);
        if (!device) return in_node(node, device.error());
        added = wiring->add(node, RobotMoverLogic(*settings, std::move(*device)));
      } else {
        auto settings = parse_pose_saver_settings(node);
        if (!settings) return std::move(settings).error();
        auto device = open_platform(settings->link, context.board, context.backend);
        if (!device) return in_node(node, device.error());
        added = wiring->add(node, PoseSaverLogic(*settings, std::move(*device)));
      }
      if (!added) return added;
    }
    return wiring->finish();
  }
};

}  // namespace

const hub_api::HubType& mir_com_hub_type() noexcept {
  static const MirComHubType type;
  return type;
}

}  // namespace hubrt::mir_com
