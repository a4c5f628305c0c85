#include "operator_settings.h"

#include <filesystem>

namespace hubrt::operator_hub {

Expected<OperatorSettings> parse_operator_settings(const config::NodeConfig& node,
                                                   const std::string& hub_file) {
  const config::YamlMap& map = node.settings;
  if (auto ok = map.only_keys({"type", "reader", "confirm_button", "screen_confirm", "allow_list"}); !ok) {
    return std::move(ok).error();
  }
  OperatorSettings settings;
  auto reader = map.string("reader");
  if (!reader) return std::move(reader).error();
  settings.reader = std::move(*reader);
  auto button = map.string_or("confirm_button", "");
  if (!button) return std::move(button).error();
  settings.confirm_button = std::move(*button);
  auto screen = map.string_or("screen_confirm", "");
  if (!screen) return std::move(screen).error();
  settings.screen_confirm = std::move(*screen);
  auto allow_list = map.string("allow_list");
  if (!allow_list) return std::move(allow_list).error();
  if (allow_list->empty()) return map.error_at("allow_list", "give the operator allow-list's path");
  std::filesystem::path path(*allow_list);
  if (path.is_relative()) path = std::filesystem::path(hub_file).parent_path() / path;
  settings.allow_list = path.lexically_normal().string();
  return settings;
}

void add_requirements(const OperatorSettings& settings, hal::BoardRequirements& requirements) {
  requirements.badge_readers.push_back(settings.reader);
  if (!settings.confirm_button.empty()) requirements.inputs.push_back(settings.confirm_button);
}

}  // namespace hubrt::operator_hub
