#include "bridge_core.h"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/sample_memory.h"
#include "hubrt/ros1/codec.h"

namespace hubrt::hubbridge {
namespace {

const msgs::FieldInfo* field_named(const msgs::TypeInfo& type, std::string_view name) {
  for (const auto& f : type.fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

}  // namespace

Expected<BridgedType> bridged_type(std::string_view name, const ros1::Messages& messages) {
  const msgs::TypeInfo* type = msgs::all_types().find(name);
  if (type == nullptr || type->descriptor == nullptr) {
    return make_error(ErrorCode::kInvalidArgument, msgs::all_types().unknown_type_message(name));
  }
  BridgedType out;
  out.type = type;
  out.ros1_name = ros1::ros1_name_of(*type);
  if (auto ok = ros1::check_matches(messages, out.ros1_name, *type); !ok) return std::move(ok).error();
  auto md5 = ros1::md5sum(messages, out.ros1_name);
  if (!md5) return std::move(md5).error();
  auto definition = ros1::full_definition(messages, out.ros1_name);
  if (!definition) return std::move(definition).error();
  out.md5sum = std::move(*md5);
  out.definition = std::move(*definition);
  return out;
}

Ros1Inbound::Ros1Inbound(BridgedType type, const ros1::Messages& expected)
    : type_(std::move(type)), expected_(expected), sample_(type_.type->size, 0) {}

Ros1Inbound::~Ros1Inbound() {
  msgs::free_contents(*type_.type, sample_.data());
}

std::string Ros1Inbound::check_publisher(const std::string& callerid, const std::string& datatype,
                                         const std::string& md5sum, const std::string& definition) {
  const std::string key = callerid + " " + md5sum + " " + datatype;
  if (const auto it = verdict_by_publisher_.find(key); it != verdict_by_publisher_.end()) return it->second;
  std::string verdict;
  if (datatype != type_.ros1_name) {
    verdict = fmt::format("ROS 1 publisher {} sends {}, the bridge carries {}", callerid, datatype,
                          type_.ros1_name);
  } else if (md5sum != type_.md5sum) {
    auto announced = ros1::parse_full_definition(definition, type_.ros1_name);
    std::string diff = announced
                           ? ros1::first_difference(expected_, *announced, type_.ros1_name)
                           : fmt::format("its definition does not parse: {}", announced.error().message);
    if (diff.empty()) diff = "the definitions agree, so its md5sum is wrong";
    verdict = fmt::format("ROS 1 publisher {} announces {} with md5sum {}, ros2/hub_msgs gives {}: {}",
                          callerid, datatype, md5sum, type_.md5sum, diff);
  }
  verdict_by_publisher_.emplace(key, verdict);
  return verdict;
}

std::optional<Ros1Inbound::HeaderStamp> Ros1Inbound::header_of_sample() const {
  // A hub State's first field: StateHeader {stamp, seq, lifecycle} (firmware/msgs/README.md).
  const msgs::FieldInfo* header = field_named(*type_.type, "header");
  if (header == nullptr || header->kind != msgs::FieldKind::kStruct) return std::nullopt;
  const msgs::FieldInfo* stamp = field_named(*header->nested, "stamp");
  const msgs::FieldInfo* seq = field_named(*header->nested, "seq");
  if (stamp == nullptr || seq == nullptr || seq->kind != msgs::FieldKind::kUInt64 ||
      stamp->kind != msgs::FieldKind::kStruct || stamp->nested->size != 8) {
    return std::nullopt;
  }
  const std::uint8_t* base = sample_.data() + header->offset;
  HeaderStamp h;
  std::memcpy(&h.sec, base + stamp->offset, 4);
  std::memcpy(&h.nanosec, base + stamp->offset + 4, 4);
  std::memcpy(&h.seq, base + seq->offset, 8);
  return h;
}

Verdict Ros1Inbound::take(std::span<const std::uint8_t> bytes, std::string* why) {
  const auto error = ros1::decode(*type_.type, bytes, sample_.data());
  if (error) {
    *why = error->message;
    return error->problem == ros1::DecodeProblem::kOverBound ? Verdict::kOverBound : Verdict::kTypeError;
  }
  const auto header = header_of_sample();
  if (header) {
    // Same seq and stamp: the very sample again (a latched publisher re-sending on reconnect).
    // A smaller seq with an older stamp is older still. A smaller seq with a newer stamp is the
    // ECU restarted: forwarded (the State header says so to every reader).
    const auto stamp_of = [](const HeaderStamp& h) { return std::pair(h.sec, h.nanosec); };
    if (last_ && header->seq <= last_->seq && stamp_of(*header) <= stamp_of(*last_)) {
      *why = fmt::format("seq {} stamped {}.{:09} was forwarded already (last: seq {})", header->seq,
                         header->sec, header->nanosec, last_->seq);
      return Verdict::kStale;
    }
    last_ = header;
  }
  return Verdict::kForward;
}

void to_ros1(const BridgedType& type, const void* sample, std::vector<std::uint8_t>& out) {
  out.clear();
  ros1::encode(*type.type, sample, out);
}

void HeardPublishers::heard(std::string_view caller_id, std::int64_t now_ns) {
  const std::lock_guard lock(mutex_);
  for (auto& [name, at] : last_) {
    if (name == caller_id) {
      at = now_ns;
      return;
    }
  }
  if (last_.size() == kMax) {
    last_.erase(std::min_element(last_.begin(), last_.end(),
                                 [](const auto& a, const auto& b) { return a.second < b.second; }));
  }
  last_.emplace_back(std::string(caller_id), now_ns);
}

std::vector<std::string> HeardPublishers::since(std::int64_t since_ns) const {
  const std::lock_guard lock(mutex_);
  std::vector<std::string> out;
  for (const auto& [name, at] : last_) {
    if (at >= since_ns) out.push_back(name);
  }
  return out;
}

}  // namespace hubrt::hubbridge
