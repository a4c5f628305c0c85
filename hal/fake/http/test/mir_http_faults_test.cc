// The REST client for real: cpp-httplib's client (hal/linux/http) on the HAL's worker thread
// (threaded_async_http.h) with the MiR decoder, against the MiR100 simulator's server on
// loopback. Every fault kind of a REST device ends in a completion that says what went wrong —
// never a hang (every call is bounded) and never a crash.
#include <gtest/gtest.h>

#include "hubrt/hal/common/threaded_async_http.h"
#include "hubrt/hal/fake/mir_sim_server.h"
#include "hubrt/hal/httplib/open_httplib.h"
#include "hubrt/protocol/mir_rest.h"

namespace hubrt::hal::fake {
namespace {

using protocol::mir::MirReply;
using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr std::string_view kAuthorization = "Basic bWlyOmhhc2g=";
// Generous: a loaded 2-core machine running sanitizer builds; the bounds below are what is
// checked (a completion arrives), not how fast.
constexpr Duration kPatience = seconds(20);

class MirHttpTest : public ::testing::Test {
 protected:
  void SetUp() override {
    MirPlatformConfig config;
    config.authorization = std::string(kAuthorization);
    platform_.emplace(config, clock_.now().mono);
    platform_->add_position("home", 0, 0, 0);
    MirSimServerOptions options;
    // Far beyond the client's timeout below, so that a client thread delayed by load still finds
    // no answer when it gives up.
    options.slow_delay = milliseconds(4000);
    auto server = start_mir_sim_server(*platform_, clock_, options);
    ASSERT_TRUE(server) << server.error().message;
    server_ = std::move(*server);
    device_ = open(std::string(kAuthorization), 64 * 1024);
  }

  std::unique_ptr<AsyncHttp<MirReply>> open(std::string authorization, std::size_t max_bytes) {
    HttpConfig config;
    config.device = "mir";
    config.host = "127.0.0.1";
    config.port = server_->port();
    config.base_path = "/api/v2.0.0";
    config.authorization = std::move(authorization);
    // Each healthy answer must come within this: with 300 ms, SlowAndMissingAnswersTimeOut failed
    // once in the ASan build on a loaded 2-core machine.
    config.read_timeout = milliseconds(1000);
    config.connect_timeout = milliseconds(1000);
    config.max_response_bytes = max_bytes;
    auto client = httplib_client::open_httplib(config);
    EXPECT_TRUE(client) << client.error().message;
    auto device = open_threaded_async_http<MirReply>(std::move(*client), protocol::mir::decode_reply,
                                                     http_request_timeout(config), describe_http(config));
    EXPECT_TRUE(device) << device.error().message;
    return std::move(*device);
  }

  // Submits and polls with the real time until the completion comes.
  HttpCompletion<MirReply> call(AsyncHttp<MirReply>& device, const HttpRequest& request) {
    SystemClock wall;
    const Result<std::uint64_t> id = device.submit(request, wall.now().mono);
    EXPECT_TRUE(id.is_ok());
    HttpCompletion<MirReply> done;
    const Time deadline = wall.now().mono + kPatience;
    while (!device.poll(wall.now().mono, done)) {
      if (wall.now().mono > deadline) {
        ADD_FAILURE() << "no completion";
        break;
      }
      std::this_thread::sleep_for(milliseconds(5));
    }
    return done;
  }

  HttpCompletion<MirReply> status() { return call(*device_, protocol::mir::get_status()); }

  ManualClock clock_;
  std::optional<MirPlatform> platform_;
  std::unique_ptr<MirSimServer> server_;
  std::unique_ptr<AsyncHttp<MirReply>> device_;
};

TEST_F(MirHttpTest, AnswersAreDecoded) {
  const HttpCompletion<MirReply> done = status();
  ASSERT_TRUE(done.transport.is_ok()) << done.transport_error.view();
  EXPECT_EQ(done.http_status, 200);
  ASSERT_TRUE(done.reply.ok) << done.reply.problem.view();
  EXPECT_EQ(done.reply.status.state_id, 3);
  const HttpCompletion<MirReply> paused =
      call(*device_, protocol::mir::set_state(protocol::mir::kStatePause));
  ASSERT_TRUE(paused.reply.ok) << paused.reply.problem.view();
  EXPECT_EQ(paused.reply.status.state_id, 4);
  EXPECT_EQ(platform_->snapshot().pause_requests, 1);
}

TEST_F(MirHttpTest, ServerErrorAndUnauthorizedAreNamed) {
  server_->set_fault(MirServerFault::kServerError);
  EXPECT_EQ(status().reply.problem.view(), "GET /status: HTTP 500 (internal server error)");
  server_->set_fault(MirServerFault::kUnauthorized);
  EXPECT_EQ(status().reply.problem.view(),
            "GET /status: HTTP 401 (unauthorized: check the board's authorization)");
  server_->set_fault(MirServerFault::kNone);
  auto wrong = open("Basic d3Jvbmc=", 64 * 1024);
  EXPECT_EQ(call(*wrong, protocol::mir::get_status()).http_status, 401) << "the platform checks the header";
  EXPECT_TRUE(status().reply.ok);
}

TEST_F(MirHttpTest, MalformedJsonIsAProblemNotACrash) {
  server_->set_fault(MirServerFault::kMalformedJson);
  const HttpCompletion<MirReply> done = status();
  EXPECT_TRUE(done.transport.is_ok());
  EXPECT_FALSE(done.reply.ok);
  EXPECT_NE(done.reply.problem.view().find("malformed JSON"), std::string_view::npos)
      << done.reply.problem.view();
}

TEST_F(MirHttpTest, SlowAndMissingAnswersTimeOut) {
  server_->set_fault(MirServerFault::kSlow);
  HttpCompletion<MirReply> done = status();
  EXPECT_EQ(done.transport.code(), ErrorCode::kTimeout) << done.transport_error.view();
  server_->set_fault(MirServerFault::kNoAnswer);
  done = status();
  EXPECT_EQ(done.transport.code(), ErrorCode::kTimeout) << done.transport_error.view();
  EXPECT_NE(done.transport_error.view().find("GET /api/v2.0.0/status"), std::string_view::npos)
      << done.transport_error.view();
  server_->set_fault(MirServerFault::kNone);
  EXPECT_TRUE(status().reply.ok) << "the platform is asked again and answers";
}

TEST_F(MirHttpTest, ARefusedConnectionIsUnavailableAndTheServerComesBack) {
  server_->go_down();
  const HttpCompletion<MirReply> done = status();
  EXPECT_EQ(done.transport.code(), ErrorCode::kUnavailable) << done.transport_error.view();
  ASSERT_TRUE(server_->come_back());
  EXPECT_TRUE(status().reply.ok);
}

TEST_F(MirHttpTest, AnAnswerOverTheSizeBoundIsCutOff) {
  for (int i = 0; i < 50; ++i) platform_->add_position("position_" + std::to_string(i), i, 0, 0);
  auto small = open(std::string(kAuthorization), 1024);
  const HttpCompletion<MirReply> done = call(*small, protocol::mir::find_position("position_49"));
  EXPECT_EQ(done.transport.code(), ErrorCode::kOutOfRange) << done.transport_error.view();
  const HttpCompletion<MirReply> found = call(*device_, protocol::mir::find_position("position_49"));
  EXPECT_TRUE(found.reply.ok) << found.reply.problem.view();
}

TEST_F(MirHttpTest, ClosingTheDeviceSendsItsLastRequest) {
  device_->set_request_on_close(protocol::mir::set_state(protocol::mir::kStatePause));
  device_.reset();
  EXPECT_EQ(platform_->snapshot().pause_requests, 1);
  EXPECT_EQ(platform_->snapshot().state_id, 4);
}

}  // namespace
}  // namespace hubrt::hal::fake
