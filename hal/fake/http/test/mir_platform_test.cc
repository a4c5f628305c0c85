// The simulated MiR100 without a network: it behaves like the platform (missions one after the
// other at its speed, pause holds it where it is, an error stops it until cleared, the battery
// drains faster while driving), and answers like the REST API (status codes, refusals).
#include "hubrt/hal/fake/mir_platform.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace hubrt::hal::fake {
namespace {

using nlohmann::json;
using std::chrono::seconds;

class MirPlatformTest : public ::testing::Test {
 protected:
  MirPlatformTest() : platform_(MirPlatformConfig{}, clock_.now().mono) {
    a_ = platform_.add_position("a", 3.0, 4.0, 0.0);
    b_ = platform_.add_position("b", 3.0, 0.0, 0.0);
  }
  MirAnswer call(std::string_view method, std::string_view path, std::string_view body = "") {
    return platform_.handle(method, path, body, "", clock_.now().mono);
  }
  json status() { return json::parse(call("GET", "/status").body); }
  int enqueue(const std::string& position) {
    const MirAnswer answer = call("POST", "/mission_queue",
                                  json{{"mission_id", platform_.config().move_mission_guid},
                                       {"parameters", {{{"id", "Position"}, {"value", position}}}}}
                                      .dump());
    EXPECT_EQ(answer.status, 201) << answer.body;
    return json::parse(answer.body)["id"].get<int>();
  }

  ManualClock clock_;
  MirPlatform platform_;
  std::string a_, b_;
};

TEST_F(MirPlatformTest, RunsTheQueueAtItsSpeedOneMissionAfterTheOther) {
  const int first = enqueue(a_);
  const int second = enqueue(b_);
  EXPECT_EQ(status()["state_id"], 5);
  clock_.advance(seconds(2));  // 1 m/s towards (3, 4), 5 m away
  json s = status();
  EXPECT_NEAR(s["position"]["x"].get<double>(), 1.2, 1e-6);
  EXPECT_NEAR(s["position"]["y"].get<double>(), 1.6, 1e-6);
  EXPECT_EQ(json::parse(call("GET", "/mission_queue/" + std::to_string(first)).body)["state"], "Executing");
  EXPECT_EQ(json::parse(call("GET", "/mission_queue/" + std::to_string(second)).body)["state"], "Pending");
  clock_.advance(seconds(4));
  EXPECT_EQ(json::parse(call("GET", "/mission_queue/" + std::to_string(first)).body)["state"], "Done");
  clock_.advance(seconds(5));
  EXPECT_EQ(json::parse(call("GET", "/mission_queue/" + std::to_string(second)).body)["state"], "Done");
  s = status();
  EXPECT_EQ(s["state_id"], 3);
  EXPECT_NEAR(s["position"]["y"].get<double>(), 0.0, 1e-6);
  EXPECT_EQ(call("GET", "/mission_queue/99").status, 404);
}

TEST_F(MirPlatformTest, PauseHoldsItAndAnErrorStopsItUntilCleared) {
  enqueue(a_);
  clock_.advance(seconds(1));
  EXPECT_EQ(call("PUT", "/status", R"({"state_id": 4})").status, 200);
  const double x = status()["position"]["x"].get<double>();
  clock_.advance(seconds(3));
  EXPECT_EQ(status()["position"]["x"].get<double>(), x);
  EXPECT_EQ(call("PUT", "/status", R"({"state_id": 3})").status, 200);
  EXPECT_EQ(status()["state_id"], 5);
  platform_.inject_error(3001, "Emergency stop", clock_.now().mono);
  EXPECT_EQ(status()["errors"][0]["code"], 3001);
  EXPECT_EQ(call("PUT", "/status", R"({"state_id": 3})").status, 409);
  EXPECT_EQ(call("PUT", "/status", R"({"clear_error": true})").status, 200);
  EXPECT_EQ(status()["state_id"], 4);
  EXPECT_EQ(call("PUT", "/status", R"({"state_id": 7})").status, 400);
  EXPECT_EQ(call("PUT", "/status", R"({"state_id": 4294967299})").status, 400);  // 3 modulo 2^32
  EXPECT_EQ(status()["state_id"], 4);
  EXPECT_EQ(call("PUT", "/status", "{not json").status, 400);
}

TEST_F(MirPlatformTest, TheBatteryDrainsFasterWhileDriving) {
  const double start = status()["battery_percentage"].get<double>();
  clock_.advance(seconds(10));
  const double idle = start - status()["battery_percentage"].get<double>();
  enqueue(a_);
  clock_.advance(seconds(4));
  const double before = status()["battery_percentage"].get<double>();
  clock_.advance(seconds(1));  // still driving (5 m at 1 m/s)
  const double driving = before - status()["battery_percentage"].get<double>();
  EXPECT_GT(idle, 0.0);
  EXPECT_GT(driving * 10, idle * 5) << "a second driving costs more than a second standing";
}

TEST_F(MirPlatformTest, SavesPositionsAndRefusesWhatTheApiRefuses) {
  const MirAnswer saved = call("POST", "/positions",
                               json{{"name", "here"},
                                    {"pos_x", 1.0},
                                    {"pos_y", 2.0},
                                    {"orientation", 45.0},
                                    {"type_id", 0},
                                    {"map_id", platform_.config().map_id}}
                                   .dump());
  EXPECT_EQ(saved.status, 201) << saved.body;
  const json list = json::parse(call("GET", "/positions").body);
  EXPECT_EQ(list.size(), 3U);
  EXPECT_EQ(list[2]["name"], "here");
  EXPECT_EQ(call("POST", "/positions", R"({"name": "x", "pos_x": 1})").status, 400);
  EXPECT_EQ(call("POST", "/mission_queue", R"({"mission_id": "nope"})").status, 400);
  MirPlatformConfig locked;
  locked.authorization = "Basic abc";
  MirPlatform guarded(locked, clock_.now().mono);
  EXPECT_EQ(guarded.handle("GET", "/status", "", "Basic wrong", clock_.now().mono).status, 401);
  EXPECT_EQ(guarded.handle("GET", "/status", "", "Basic abc", clock_.now().mono).status, 200);
}

}  // namespace
}  // namespace hubrt::hal::fake
