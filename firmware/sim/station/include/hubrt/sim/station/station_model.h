// The station's physical world, which no hub sees whole and which couples them: where the robot
// is, which end-effector is on its tool changer and which sit in their dock slots, where the
// ladder frame is, where the smart tool (and so its arm) is. It watches the actuators the hubs
// drive (the changer's lock and gripper valves on the RSP ECU, the lift on the Tool ECU) and
// decides what the hubs' sensors show (the RSP's tool-ID lines, the Dock's presence sensors, the
// smart tool's arm sensors).
//
// Physics, in short (hubs/station/README.md has the whole of it):
//   - The robot moves between places and dock slots; a move takes the configured travel time.
//   - A tool attaches when the changer's lock closes with the robot at that tool's dock slot and
//     the tool in it. When the lock opens, the tool on the changer is released: into its slot if
//     the robot is there, otherwise it drops — the failure the RSP ECU's interlock must prevent.
//   - A tool on the robot at its own slot sits in the slot (its presence sensor sees it).
//   - The ladder frame is grabbed when the gripper of the ladder-frame tool closes where the frame
//     lies, and put down where the gripper opens (it drops where it cannot lie).
//   - The smart tool's arm sensors follow the tool: in its holder they follow the lift, on the
//     robot they show "operating" above the engine and "out of range" elsewhere.
//   - With a mobile platform configured, the kit is at the station only while the platform stands
//     at its station position: it arrives with a ladder frame on it, and when it leaves, a frame
//     on the kit leaves with it ("away"); the robot at the kit then is a collision.
//
// Pure logic: time is passed in, no DDS. Not thread-safe.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/sim/station/station_config.h"

namespace hubrt::sim::station {

enum class ToolPlace : std::uint8_t { kDock, kRobot, kDropped };
std::string_view to_string(ToolPlace place) noexcept;

enum class ArmReading : std::uint8_t { kHome, kPreHome, kOperating, kOutOfRange };
std::string_view to_string(ArmReading reading) noexcept;

// Where the kit is. Without a mobile platform configured it is always at the station.
enum class KitPlace : std::uint8_t { kAtStation, kAway, kUnknown };
// "at_station", "away", "unknown" (the platform's State never heard, or lost).
std::string_view to_string(KitPlace place) noexcept;

// What the mobile platform's State says (RobotMoverState's moving and actual_pose).
struct PlatformReport {
  bool moving = false;
  std::string_view pose;  // the position the last finished move reached; "" while moving or unknown
};

// One input of one hub, as the world makes it look.
struct WorldInput {
  HubRole hub;
  std::string_view signal;  // points into the model's configuration
  bool active = false;
};

class StationModel {
 public:
  // The world as the configuration says it starts.
  explicit StationModel(StationConfig config);

  [[nodiscard]] const StationConfig& config() const noexcept { return config_; }

  // --- What the hubs' simulated actuators do (from /sim/<hub>/signals) ---------------------------
  // A valve's actuator position; the lock and gripper valves of the configuration matter, others
  // are ignored. The first observation of each only says where it is (nothing attaches or
  // drops); later changes act at `now` on the world as it is then.
  void observe_valve(std::string_view valve, bool energised, Time now);
  // The smart tool's lift, by Modbus device name (others are ignored).
  void observe_lift(std::string_view device, double position_mm);

  // --- What the scenario makes the world do ----------------------------------------------------
  // "move_robot" to `location`, "restock", "reset". Brings the world to `now` first.
  // Errors (kInvalidArgument, nothing changes): unknown action or location; restock while the
  // robot holds the frame.
  Expected<void> command(std::string_view action, std::string_view location, Time now);

  // --- What the mobile platform does (its State, when one is configured) ------------------------
  // The platform's State at `now`. Ignored without a platform configured. The kit arrives when
  // the platform stands at its station position, and leaves when it moves or stands elsewhere.
  void observe_platform(const PlatformReport& report, Time now);

  // Brings the world to `now`: a robot under way arrives when its travel time is over; a platform
  // whose State has not come for its timeout is lost (the kit counts as gone).
  void advance(Time now);

  // --- What the world looks like --------------------------------------------------------------
  // Every input the world decides, for every hub.
  [[nodiscard]] std::vector<WorldInput> inputs() const;

  // "" while moving.
  [[nodiscard]] const std::string& robot_at() const noexcept { return robot_at_; }
  [[nodiscard]] const std::string& robot_moving_to() const noexcept { return moving_to_; }
  // The tool on the changer, or nullptr.
  [[nodiscard]] const ToolConfig* on_robot() const noexcept;
  [[nodiscard]] ToolPlace tool_place(std::size_t tool) const noexcept { return tools_[tool]; }
  // "kit", "gripper", "engine", "dropped", "away" (left with the mobile platform).
  [[nodiscard]] const std::string& ladder_frame() const noexcept { return frame_at_; }
  // Unknown until the RSP ECU's valves were observed.
  [[nodiscard]] std::optional<bool> lock_open() const noexcept { return lock_open_; }
  [[nodiscard]] std::optional<bool> gripper_closed() const noexcept { return gripper_closed_; }
  [[nodiscard]] std::optional<double> lift_mm() const noexcept { return lift_mm_; }
  [[nodiscard]] ArmReading arm() const noexcept;
  [[nodiscard]] KitPlace kit() const noexcept { return kit_; }
  // What went wrong (dropped tools and frames, collisions), oldest first, until a reset.
  [[nodiscard]] const std::vector<std::string>& faults() const noexcept { return faults_; }

  static constexpr std::string_view kGripper = "gripper";
  static constexpr std::string_view kDropped = "dropped";
  static constexpr std::string_view kAway = "away";

 private:
  void start_over();
  void kit_becomes(KitPlace place);
  // The kit's place (the mobile platform's), or "" without a platform.
  [[nodiscard]] std::string_view kit_place() const noexcept;
  [[nodiscard]] bool kit_here() const noexcept { return kit_ == KitPlace::kAtStation; }
  // Where restock and reset put the frame: its start, unless that is a kit that is not here.
  [[nodiscard]] std::string fresh_frame_place() const;
  void arrive();
  void lock_closed();
  void lock_opened();
  void gripper_changed(bool closed);
  void release_tool(std::size_t tool, std::string_view why);
  [[nodiscard]] std::optional<std::size_t> tool_index(std::string_view name) const noexcept;
  [[nodiscard]] ArmReading arm_in_holder() const noexcept;

  StationConfig config_;
  std::vector<ToolPlace> tools_;
  std::string robot_at_;
  std::string moving_to_;
  Time arrives_at_{};
  std::optional<std::size_t> attached_;
  std::string frame_at_;
  std::optional<bool> lock_open_;
  std::optional<bool> gripper_closed_;
  std::optional<double> lift_mm_;
  std::vector<std::string> faults_;
  KitPlace kit_ = KitPlace::kAtStation;
  std::optional<Time> platform_heard_;
};

}  // namespace hubrt::sim::station
