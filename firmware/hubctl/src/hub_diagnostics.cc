#include "hub_diagnostics.h"

#include <charconv>
#include <thread>

#include <fmt/format.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/json.h"

#include "sample_decoder.h"

namespace hubrt::hubctl {
namespace {

constexpr std::string_view kDiagnosticsTopic = "/diagnostics";
constexpr std::string_view kDiagnosticsType = "diagnostic_msgs/msg/DiagnosticArray";

std::optional<double> number(const std::string& text) {
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

bool complete(const DiagnosticsByHub& hubs, const std::set<std::string>& wanted) {
  for (const std::string& hub : wanted) {
    const auto it = hubs.find(hub);
    if (it == hubs.end() || it->second.hub_type.empty()) return false;
  }
  return !wanted.empty();
}

}  // namespace

void absorb_diagnostics(const nlohmann::ordered_json& array, DiagnosticsByHub& hubs) {
  const auto statuses = array.find("status");
  if (statuses == array.end() || !statuses->is_array()) return;
  for (const auto& status : *statuses) {
    const std::string name = status.value("name", "");
    const auto colon = name.find(": ");
    if (colon == std::string::npos) continue;
    const std::string hub = name.substr(0, colon);
    const std::string part = name.substr(colon + 2);
    std::map<std::string, std::string> values;
    if (const auto kv = status.find("values"); kv != status.end() && kv->is_array()) {
      for (const auto& pair : *kv) values[pair.value("key", "")] = pair.value("value", "");
    }
    if (const auto type = values.find("hub_type"); type != values.end()) {
      HubDiagnostics& d = hubs[hub];
      d.hub_type = type->second;
      if (const auto it = values.find("period_ms"); it != values.end()) d.period_ms = number(it->second);
      if (const auto it = values.find("command_timeout_ms"); it != values.end())
        d.command_timeout_ms = number(it->second);
      if (const auto it = values.find("immediate_state_interval_ms"); it != values.end())
        d.immediate_state_interval_ms = number(it->second);
    } else if (const auto node_type = values.find("node_type"); node_type != values.end()) {
      hubs[hub].node_types[part] = node_type->second;
    }
  }
}

Expected<DiagnosticsByHub> listen_for_diagnostics(const dds::Participant& participant,
                                                  const std::set<std::string>& wanted, double timeout_s) {
  DiagnosticsByHub hubs;
  const msgs::TypeInfo* type = msgs::all_types().find(kDiagnosticsType);
  if (type == nullptr || type->descriptor == nullptr) {
    return make_error(ErrorCode::kInternal,
                      fmt::format("{} is not built into this hubctl", kDiagnosticsType));
  }
  auto topic = dds::UntypedTopic::create(participant, *type->descriptor, kDiagnosticsTopic);
  if (!topic) return std::move(topic).error();
  auto reader = dds::UntypedReader::create(participant, *topic);
  if (!reader) return std::move(reader).error();
  dds::UntypedSample sample(*type->descriptor);
  SampleDecoder decoder("hubctl", std::string(kDiagnosticsTopic));
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline && !complete(hubs, wanted)) {
    const Result<bool> taken = reader->take_next(sample.data());
    if (!taken.is_ok()) break;
    if (taken.value()) {
      // A sample that cannot be read is reported and skipped; the others still count.
      if (auto value = decoder.decode(*type, sample.data())) absorb_diagnostics(*value, hubs);
      continue;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return hubs;
}

std::optional<BridgeQuiet> bridge_quiet(const nlohmann::ordered_json& status) {
  if (!status.is_object()) return std::nullopt;
  std::string silent;
  std::string dropping;
  const auto values = status.find("values");
  if (values == status.end() || !values->is_array()) return std::nullopt;
  for (const auto& kv : *values) {
    if (!kv.is_object() || !kv.contains("key") || !kv["key"].is_string() || !kv.contains("value") ||
        !kv["value"].is_string())
      continue;
    if (kv["key"] == "silent") silent = kv["value"].get<std::string>();
    if (kv["key"] == "dropping") dropping = kv["value"].get<std::string>();
  }
  const auto message = status.find("message");
  const std::string text = message != status.end() && message->is_string() ? message->get<std::string>() : "";
  if (dropping == "true") return BridgeQuiet{"DROPPED OVER A BOUND", text};
  if (silent == "true") return BridgeQuiet{"SILENT", text.empty() ? "silent" : text};
  return std::nullopt;
}

Expected<std::map<std::string, BridgeQuiet>> listen_for_quiet_bridges(const dds::Participant& participant,
                                                                      double duration_s) {
  const msgs::TypeInfo* type = msgs::all_types().find(kDiagnosticsType);
  if (type == nullptr || type->descriptor == nullptr) {
    return make_error(ErrorCode::kInternal,
                      fmt::format("{} is not built into this hubctl", kDiagnosticsType));
  }
  auto topic = dds::UntypedTopic::create(participant, *type->descriptor, kDiagnosticsTopic);
  if (!topic) return std::move(topic).error();
  auto reader = dds::UntypedReader::create(participant, *topic);
  if (!reader) return std::move(reader).error();
  dds::UntypedSample sample(*type->descriptor);
  SampleDecoder decoder("hubctl", std::string(kDiagnosticsTopic));
  std::map<std::string, BridgeQuiet> quiet;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(duration_s);
  while (std::chrono::steady_clock::now() < deadline) {
    const Result<bool> taken = reader->take_next(sample.data());
    if (!taken.is_ok()) break;
    if (!taken.value()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      continue;
    }
    const auto array = decoder.decode(*type, sample.data());
    if (!array || !array->contains("status") || !(*array)["status"].is_array()) continue;
    for (const auto& status : (*array)["status"]) {
      std::string dds_topic;
      for (const auto& kv : status.value("values", nlohmann::ordered_json::array())) {
        if (kv.value("key", "") == "dds_topic") dds_topic = kv.value("value", "");
      }
      if (dds_topic.empty()) continue;  // not a hubbridge bridge
      if (auto why = bridge_quiet(status)) {
        quiet[dds_topic] = std::move(*why);
      } else {
        quiet.erase(dds_topic);
      }
    }
  }
  return quiet;
}

}  // namespace hubrt::hubctl
