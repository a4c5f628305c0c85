// A ROS 1 message from a publisher hubbridge does not trust, through the ROS 1 codec
// (hubrt::ros1::decode) into a hub type's sample; what decodes must encode to the same bytes.
// Input: byte 0 picks the type (kTypes, modulo), the rest is the ROS 1 serialisation. With byte 0's
// high bit set the rest is instead a ROS 1 full definition (a publisher's connection header),
// parsed and compared with the hub type's, as hubbridge's publisher check does.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/definitions.h"
#include "hubrt/msgs/sample_memory.h"
#include "hubrt/ros1/codec.h"
#include "hubrt/ros1/definition.h"

namespace {

constexpr const char* kTypes[] = {"hub_msgs/msg/DockState",  "hub_msgs/msg/DockCommand",
                                  "hub_msgs/msg/SimSignals", "hub_msgs/msg/ToolEcuState",
                                  "hub_msgs/msg/RspState",   "hub_msgs/msg/StationState"};
constexpr std::size_t kTypeCount = sizeof kTypes / sizeof kTypes[0];

// The hub types' ROS 1 definitions, built once from the .msg texts built into the harness.
const hubrt::ros1::Messages& hub_messages() {
  static const hubrt::ros1::Messages messages = [] {
    auto loaded = hubrt::ros1::load_definitions_as_ros1(hubrt::msgs::msg_definitions());
    if (!loaded) std::abort();
    return *loaded;
  }();
  return messages;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const hubrt::msgs::TypeInfo* type = hubrt::msgs::all_types().find(kTypes[(data[0] & 0x7F) % kTypeCount]);
  if (type == nullptr) std::abort();
  if ((data[0] & 0x80) != 0) {
    const std::string name = hubrt::ros1::ros1_name_of(*type);
    const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
    auto announced = hubrt::ros1::parse_full_definition(text, name);
    if (!announced) return 0;
    (void)hubrt::ros1::first_difference(hub_messages(), *announced, name);
    (void)hubrt::ros1::md5sum(*announced, name);
    (void)hubrt::ros1::full_definition(*announced, name);
    return 0;
  }
  std::vector<std::uint8_t> sample(type->size, 0);
  const std::span<const std::uint8_t> wire(data + 1, size - 1);
  if (!hubrt::ros1::decode(*type, wire, sample.data())) {
    std::vector<std::uint8_t> again;
    hubrt::ros1::encode(*type, sample.data(), again);
    if (again.size() != wire.size() || !std::equal(again.begin(), again.end(), wire.begin())) std::abort();
  }
  hubrt::msgs::free_contents(*type, sample.data());
  return 0;
}
