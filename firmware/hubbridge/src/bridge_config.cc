#include "bridge_config.h"

#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "hubrt/config/yaml_map.h"
#include "hubrt/dds/ros_names.h"

namespace hubrt::hubbridge {
namespace {

Expected<BridgeConfig> bridge_of(const config::YamlMap& map) {
  if (auto ok = map.only_keys({"ros1_topic", "dds_topic", "type", "direction", "qos", "depth", "latch"});
      !ok) {
    return std::move(ok).error();
  }
  BridgeConfig bridge;
  auto ros1 = map.string("ros1_topic");
  auto dds = map.string("dds_topic");
  auto type = map.string("type");
  auto direction = map.choice("direction", {"ros1_to_dds", "dds_to_ros1"});
  auto qos = map.choice_or("qos", "reliable", {"reliable", "best_effort"});
  auto depth = map.integer_or("depth", 10, 1, 1000);
  auto latch = map.boolean_or("latch", false);
  for (const Expected<std::string>* e : {&ros1, &dds, &type, &direction, &qos}) {
    if (!*e) return e->error();
  }
  if (!depth) return std::move(depth).error();
  if (!latch) return std::move(latch).error();
  // ROS 1 and ROS 2 topic names share the grammar hubrt checks (a subset of both).
  for (const std::string* topic : {&*ros1, &*dds}) {
    if (auto ok = dds::validate_ros_topic_name(*topic); !ok) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: {}: {}", map.file(), map.path(), ok.error().message));
    }
  }
  bridge.ros1_topic = *ros1;
  bridge.dds_topic = *dds;
  bridge.type = *type;
  bridge.direction = *direction == "ros1_to_dds" ? Direction::kRos1ToDds : Direction::kDdsToRos1;
  bridge.reliability = *qos == "reliable" ? Reliability::kReliable : Reliability::kBestEffort;
  bridge.depth = static_cast<int>(*depth);
  bridge.latch = *latch;
  if (bridge.latch && bridge.direction == Direction::kRos1ToDds) {
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("{}: {}: latch applies to dds_to_ros1 bridges only", map.file(), map.path()));
  }
  return bridge;
}

Expected<BridgeFile> from_map(const Expected<config::YamlMap>& root, const std::string& base_dir) {
  if (!root) return root.error();
  if (auto ok =
          root->only_keys({"name", "msg_dir", "silent_after_ms", "register_lost_publishers", "bridges"});
      !ok)
    return std::move(ok).error();
  BridgeFile file;
  auto name = root->string_or("name", "hubbridge");
  auto msg_dir = root->string_or("msg_dir", "");
  auto silent = root->integer_or("silent_after_ms", 2000, 10, 3600000);
  auto register_lost = root->boolean_or("register_lost_publishers", true);
  auto bridges = root->list_of_maps("bridges");
  if (!name) return std::move(name).error();
  if (!register_lost) return std::move(register_lost).error();
  if (!msg_dir) return std::move(msg_dir).error();
  if (!silent) return std::move(silent).error();
  if (!bridges) return std::move(bridges).error();
  file.name = *name;
  if (!msg_dir->empty()) {
    file.msg_dir = (std::filesystem::path(base_dir) / *msg_dir).lexically_normal().string();
  }
  file.silent_after_s = static_cast<double>(*silent) / 1000.0;
  file.register_lost_publishers = *register_lost;
  // One writer per topic and direction: two bridges publishing one topic would be the duplicate
  // publishers a static bridge exists to avoid.
  std::set<std::string> published;
  for (const auto& map : *bridges) {
    auto bridge = bridge_of(map);
    if (!bridge) return std::move(bridge).error();
    const std::string out = bridge->direction == Direction::kRos1ToDds ? "dds " + bridge->dds_topic
                                                                       : "ros1 " + bridge->ros1_topic;
    if (!published.insert(out).second) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: {}: a second bridge publishes {}", map.file(), map.path(), out));
    }
    file.bridges.push_back(std::move(*bridge));
  }
  if (file.bridges.empty()) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: no bridges", root->file()));
  }
  return file;
}

}  // namespace

Expected<BridgeFile> load_bridge_file(const std::string& path) {
  return from_map(config::YamlMap::load_file(path), std::filesystem::path(path).parent_path().string());
}

Expected<BridgeFile> load_bridge_text(const std::string& text, const std::string& name,
                                      const std::string& base_dir) {
  return from_map(config::YamlMap::load_string(text, name), base_dir);
}

}  // namespace hubrt::hubbridge
