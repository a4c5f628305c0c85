// The subset of MiR's REST API v2.0.0 (MiR100) the mir_com hub speaks, as a pure codec: fixed-size
// requests built without allocating (for the cycle), and the decoder that turns an answer into a
// fixed-size MirReply (run on the HAL's HTTP worker thread; it parses JSON with nlohmann-json and
// never throws). The simulator (hal/fake/http) serves the same fields. Endpoints, fields and the
// sources relied on: docs/protocols/mir-rest.md.
#pragma once

#include <cstdint>
#include <string_view>

#include "hubrt/hal/http_client.h"

namespace hubrt::protocol::mir {

// state_id values of GET/PUT /status (MiR REST API v2.0.0; docs/protocols/mir-rest.md).
inline constexpr int kStateReady = 3;
inline constexpr int kStatePause = 4;
inline constexpr int kStateExecuting = 5;
inline constexpr int kStateEmergencyStop = 10;
inline constexpr int kStateError = 12;

// What a request asked, carried in HttpRequest::tag so that the decoder knows what to read.
enum class MirCall : std::uint32_t {
  kNone = 0,
  kGetStatus,     // GET /status
  kSetState,      // PUT /status {"state_id": 3|4}
  kClearError,    // PUT /status {"clear_error": true}
  kFindPosition,  // GET /positions, the one named HttpRequest::key
  kPostPosition,  // POST /positions
  kPostMission,   // POST /mission_queue
  kGetMission,    // GET /mission_queue/{id}
  kClearQueue,    // DELETE /mission_queue
};

[[nodiscard]] std::string_view to_string(MirCall call) noexcept;

// Names of positions and robots the hub sends: letters, digits, '_', '-', '.', ' ' (no JSON
// escaping needed), 1 to 40 bytes (MiR's limit for a position name).
inline constexpr std::size_t kMaxPositionName = 40;
[[nodiscard]] bool valid_position_name(std::string_view name) noexcept;
// A MiR GUID as the API writes them (hex digits and '-', 1 to 40 bytes).
[[nodiscard]] bool valid_guid(std::string_view guid) noexcept;

struct MirStatus {
  int state_id = 0;
  hal::FixedText<32> state_text;  // "Ready", "Pause", "Executing", "Error", ...
  float x = 0;                    // m, map frame
  float y = 0;
  float yaw_deg = 0;  // position.orientation, degrees
  float battery_percent = 0;
  int mission_queue_id = 0;  // 0: none
  hal::FixedText<40> map_id;
  hal::FixedText<96> mission_text;
  int error_count = 0;  // entries in "errors"
  hal::FixedText<96> first_error;
};

// A decoded answer. `ok`: a 2xx answer whose fields were all understood; otherwise `problem`
// says why, e.g. "HTTP 401 (unauthorized)", "malformed JSON (...)", "no position named 'dock'".
struct MirReply {
  MirCall call = MirCall::kNone;
  bool ok = false;
  hal::FixedText<140> problem;
  MirStatus status;                  // kGetStatus, kSetState, kClearError (MiR answers the status)
  hal::FixedText<40> guid;           // kFindPosition (found), kPostPosition (created)
  int mission_id = 0;                // kPostMission, kGetMission
  hal::FixedText<16> mission_state;  // kPostMission, kGetMission: Pending, Executing, Done, Aborted
};

// Request builders. Preconditions: names valid_position_name, guids valid_guid (what does not
// fit leaves the request's path empty, which AsyncHttp::submit refuses).
[[nodiscard]] hal::HttpRequest get_status() noexcept;
[[nodiscard]] hal::HttpRequest set_state(int state_id) noexcept;
[[nodiscard]] hal::HttpRequest clear_error() noexcept;
[[nodiscard]] hal::HttpRequest find_position(std::string_view name) noexcept;
[[nodiscard]] hal::HttpRequest post_position(std::string_view name, float x, float y, float yaw_deg,
                                             std::string_view map_id) noexcept;
// The move mission `mission_guid` with its position parameter `parameter` set to `position_guid`.
[[nodiscard]] hal::HttpRequest post_mission(std::string_view mission_guid, std::string_view parameter,
                                            std::string_view position_guid) noexcept;
[[nodiscard]] hal::HttpRequest get_mission(int mission_id) noexcept;
[[nodiscard]] hal::HttpRequest clear_queue() noexcept;

// The HttpDecoder of the mir_com hub (threaded_async_http.h): reads `response` as the answer to
// `request` (by its tag) into `reply`. Never throws.
void decode_reply(const hal::HttpRequest& request, const hal::HttpResponse& response,
                  MirReply& reply) noexcept;

}  // namespace hubrt::protocol::mir
