// A simulated MiR100 behind its REST API v2.0.0 (the subset of docs/protocols/mir-rest.md): a
// platform that drives between named positions at its speed, drains its battery, runs the
// missions of its queue one after the other, can be paused, continued and put in error, and
// answers REST requests as the robot does (status codes, JSON bodies). Time is passed in: the
// server (mir_sim_server.h) gives it its clock's now; tests call handle() directly.
#pragma once

#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/time.h"

namespace hubrt::hal::fake {

struct MirPlatformConfig {
  std::string robot_name = "MiR_sim";
  std::string authorization;  // the Authorization value it accepts; empty: any
  std::string move_mission_guid = "a1b2c3d4-0000-4000-8000-000000000001";  // "move to position"
  std::string position_parameter = "Position";                             // its position parameter's id
  std::string map_id = "5d2f1a3c-0000-4000-8000-000000000001";
  double speed_m_s = 1.0;  // MiR100: up to 1.5 m/s
  double turn_deg_s = 90.0;
  double battery_start_percent = 90.0;
  double drain_idle_percent_s = 0.002;
  double drain_moving_percent_s = 0.02;
  double start_x = 0, start_y = 0, start_yaw_deg = 0;  // where it stands at start
};

struct MirAnswer {
  int status = 200;
  std::string body;  // JSON (or not, with the malformed-JSON fault)
};

// Thread-safe: every member may be called from any thread (one mutex).
class MirPlatform {
 public:
  MirPlatform(MirPlatformConfig config, Time now);

  // Declares a position on the map; returns its guid.
  std::string add_position(std::string_view name, double x, double y, double yaw_deg);

  // One REST request as the robot answers it. `path` is what follows the base path
  // ("/status", "/mission_queue/3"); `authorization` the request's header value.
  MirAnswer handle(std::string_view method, std::string_view path, std::string_view body,
                   std::string_view authorization, Time now);

  // Moves the world on to `now` (handle() does this too).
  void advance(Time now);

  // --- Faults and observations, for tests and the sim bridge -------------------------------------
  // The platform stops in state Error with this error (e.g. an emergency stop) until a
  // PUT /status {"clear_error": true}.
  void inject_error(int code, std::string_view description, Time now);
  void set_battery_percent(double percent);

  struct Snapshot {
    int state_id = 0;
    double x = 0, y = 0, yaw_deg = 0;
    double battery_percent = 0;
    int missions_pending = 0;  // Pending + Executing
    int pause_requests = 0;    // PUT /status state_id 4 received
  };
  [[nodiscard]] Snapshot snapshot() const;
  [[nodiscard]] const MirPlatformConfig& config() const noexcept { return config_; }

 private:
  struct Position {
    std::string guid, name;
    double x = 0, y = 0, yaw_deg = 0;
  };
  struct Mission {
    int id = 0;
    std::string position_guid;
    std::string state;  // Pending, Executing, Done, Aborted
  };

  void advance_locked(Time now);
  void start_next_mission();
  Mission* executing();
  const Position* position(std::string_view guid) const;
  MirAnswer status_json() const;
  MirAnswer put_status(std::string_view body, Time now);
  MirAnswer post_position(std::string_view body);
  MirAnswer post_mission(std::string_view body);
  MirAnswer mission_json(int id) const;
  MirAnswer clear_queue();

  MirPlatformConfig config_;
  mutable std::mutex mutex_;
  Time last_{};
  int state_id_ = 3;  // Ready
  double x_ = 0, y_ = 0, yaw_deg_ = 0;
  double battery_ = 0;
  std::vector<Position> positions_;
  std::vector<Mission> queue_;
  int next_mission_id_ = 1;
  int next_guid_ = 1;
  int error_code_ = 0;
  std::string error_text_;
  int pause_requests_ = 0;
};

}  // namespace hubrt::hal::fake
