// The MiR codec without a network: requests as MiR's REST API v2.0.0 takes them, and answers —
// good, refused, malformed — decoded into a reply that says what was wrong, never a throw.
#include "hubrt/protocol/mir_rest.h"

#include <limits>
#include <string>

#include <gtest/gtest.h>

namespace hubrt::protocol::mir {
namespace {

MirReply decode(const hal::HttpRequest& request, int status, std::string body) {
  hal::HttpResponse response;
  response.status = status;
  response.body = std::move(body);
  MirReply reply;
  decode_reply(request, response, reply);
  return reply;
}

constexpr const char* kStatus =
    R"({"state_id": 5, "state_text": "Executing", "position": {"x": 1.5, "y": -2.25, "orientation": 90.0},
        "battery_percentage": 77.5, "mission_queue_id": 12, "map_id": "5d2f1a3c-0000-4000-8000-000000000001",
        "mission_text": "Moving", "errors": []})";

TEST(MirRequests, AreBuiltAsTheApiTakesThem) {
  const hal::HttpRequest pause = set_state(kStatePause);
  EXPECT_EQ(pause.method, hal::HttpMethod::kPut);
  EXPECT_EQ(pause.path.view(), "/status");
  EXPECT_EQ(pause.body.view(), R"({"state_id": 4})");
  EXPECT_EQ(clear_error().body.view(), R"({"clear_error": true})");
  const hal::HttpRequest mission = post_mission("a1b2-c3", "Position", "00ff-01");
  EXPECT_EQ(mission.path.view(), "/mission_queue");
  EXPECT_EQ(mission.body.view(),
            R"({"mission_id": "a1b2-c3", "parameters": [{"id": "Position", "value": "00ff-01"}]})");
  EXPECT_EQ(get_mission(42).path.view(), "/mission_queue/42");
  EXPECT_EQ(clear_queue().method, hal::HttpMethod::kDelete);
  const hal::HttpRequest save = post_position("kit pickup", 1.5F, -2.0F, 90.0F, "5d2f-01");
  EXPECT_EQ(
      save.body.view(),
      R"({"name": "kit pickup", "pos_x": 1.500, "pos_y": -2.000, "orientation": 90.00, "type_id": 0, "map_id": "5d2f-01"})");
  // Names the API would need escaped, or guids that are not: no request (an empty path).
  EXPECT_TRUE(find_position("a\"b").path.empty());
  EXPECT_TRUE(post_mission("not a guid", "Position", "00ff").path.empty());
  EXPECT_TRUE(post_position(std::string(41, 'a'), 0, 0, 0, "5d2f").path.empty());
}

TEST(MirDecode, ReadsTheStatus) {
  const MirReply reply = decode(get_status(), 200, kStatus);
  ASSERT_TRUE(reply.ok) << reply.problem.view();
  EXPECT_EQ(reply.status.state_id, 5);
  EXPECT_EQ(reply.status.state_text.view(), "Executing");
  EXPECT_FLOAT_EQ(reply.status.x, 1.5F);
  EXPECT_FLOAT_EQ(reply.status.y, -2.25F);
  EXPECT_FLOAT_EQ(reply.status.yaw_deg, 90.0F);
  EXPECT_FLOAT_EQ(reply.status.battery_percent, 77.5F);
  EXPECT_EQ(reply.status.mission_queue_id, 12);
  EXPECT_EQ(reply.status.error_count, 0);
}

TEST(MirDecode, FindsAPositionByNameAndSaysWhenThereIsNone) {
  const std::string list = R"([{"guid": "aa-01", "name": "home"}, {"guid": "aa-02", "name": "kit"}])";
  const MirReply found = decode(find_position("kit"), 200, list);
  ASSERT_TRUE(found.ok) << found.problem.view();
  EXPECT_EQ(found.guid.view(), "aa-02");
  const MirReply missing = decode(find_position("dock"), 200, list);
  EXPECT_FALSE(missing.ok);
  EXPECT_EQ(missing.problem.view(), "GET /positions: the platform has no position named 'dock'");
}

TEST(MirDecode, RefusalsMalformedJsonAndWrongTypesAreProblemsNotCrashes) {
  EXPECT_EQ(decode(get_status(), 401, "").problem.view(),
            "GET /status: HTTP 401 (unauthorized: check the board's authorization)");
  EXPECT_EQ(decode(get_status(), 500, "{}").problem.view(), "GET /status: HTTP 500 (internal server error)");
  EXPECT_EQ(decode(get_status(), 200, R"({"state_id": 3, "position": {)").problem.view(),
            "GET /status: malformed JSON in the answer (29 bytes)");
  EXPECT_EQ(decode(get_status(), 200, R"({"state_id": "3"})").problem.view(),
            "GET /status: no number 'state_id'");
  EXPECT_EQ(decode(get_status(), 200, R"([1, 2])").problem.view(), "GET /status: no number 'state_id'");
  EXPECT_EQ(decode(get_mission(3), 200, R"({"id": 3, "state": 7})").problem.view(),
            "GET /mission_queue/{id}: no string 'state'");
  const MirReply huge = decode(get_status(), 200, R"({"state_id": 1e999})");
  EXPECT_FALSE(huge.ok);
  EXPECT_TRUE(decode(clear_queue(), 204, "").ok);
}

// The status above with the value of `key` (wherever it is) replaced by `value`.
std::string status_with(const std::string& key, const std::string& value) {
  std::string body = kStatus;
  const std::string quoted = "\"" + key + "\": ";
  const std::size_t at = body.find(quoted) + quoted.size();
  const std::size_t end = body.find_first_of(",}", at);
  return body.replace(at, end - at, value);
}

// Numbers JSON allows but the field's type cannot hold are problems, not a cast: a plain cast of
// 1e300 to int is undefined behaviour (the fuzz tier's crash of 2026-11-28).
TEST(MirDecode, NumbersOutsideTheFieldsRangeAreProblems) {
  ASSERT_TRUE(decode(get_status(), 200, status_with("state_id", "5")).ok);
  EXPECT_EQ(decode(get_status(), 200, status_with("state_id", "1e300")).problem.view(),
            "GET /status: 'state_id' is out of range: 1e+300");
  EXPECT_EQ(decode(get_status(), 200, status_with("state_id", "2147483648")).problem.view(),
            "GET /status: 'state_id' is out of range: 2147483648");
  EXPECT_EQ(decode(get_status(), 200, status_with("state_id", "-2147483649")).problem.view(),
            "GET /status: 'state_id' is out of range: -2147483649");
  EXPECT_EQ(decode(get_status(), 200, status_with("state_id", "18446744073709551615")).problem.view(),
            "GET /status: 'state_id' is out of range: 18446744073709551615");
  EXPECT_EQ(decode(get_status(), 200, status_with("state_id", "5.5")).problem.view(),
            "GET /status: 'state_id' is out of range: 5.5");
  EXPECT_EQ(decode(get_status(), 200, status_with("state_id", "5.0")).status.state_id, 5);
  EXPECT_EQ(decode(get_status(), 200, status_with("state_id", "-2147483648")).status.state_id,
            std::numeric_limits<int>::min());
  EXPECT_EQ(decode(get_status(), 200, status_with("x", "1e300")).problem.view(),
            "GET /status: 'position': 'x' is out of range: 1e+300");
  EXPECT_EQ(decode(get_status(), 200, status_with("battery_percentage", "-1e39")).problem.view(),
            "GET /status: 'battery_percentage' is out of range: -1e+39");
  EXPECT_FLOAT_EQ(decode(get_status(), 200, status_with("x", "3")).status.x, 3.0F);
  EXPECT_EQ(decode(get_status(), 200, status_with("mission_queue_id", "1e10")).problem.view(),
            "GET /status: 'mission_queue_id' is out of range: 10000000000.0");
  EXPECT_EQ(decode(get_status(), 200, status_with("mission_queue_id", "null")).status.mission_queue_id, 0);
  EXPECT_EQ(decode(get_mission(3), 200, R"({"id": 1e300, "state": "Done"})").problem.view(),
            "GET /mission_queue/{id}: 'id' is out of range: 1e+300");
  // An error's code is only shown: any number is shown as it came.
  const MirReply error =
      decode(get_status(), 200, status_with("errors", R"([{"code": 1e300, "description": "x"}])"));
  ASSERT_TRUE(error.ok) << error.problem.view();
  EXPECT_EQ(error.status.first_error.view(), "1e+300: x");
}

}  // namespace
}  // namespace hubrt::protocol::mir
