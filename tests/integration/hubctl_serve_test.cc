// hubctl serve (the operator screen) against the real hubd running the operator hub on its test
// board (fake backend, simulated RFID reader), over loopback in the test's own DDS domain and on a
// free TCP port: the page loads, server-sent events deliver a State change (a badge verifies Anna),
// a "done" press without a verified operator is refused (409) and the hub counts nothing, and with
// Anna verified it is accepted and the hub's confirm_seq grows. Plus the guards: no press without
// the page's header, none from a foreign Host, none twice within the interval. And hubctl watch, which
// shares the screen's discovery (station_watch), still shows the panel.
#include <httplib.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/hub_process.h"

#include "operator_messages.h"

namespace hubrt::integration {
using test_support::HubProcess;
using test_support::HubProcessOptions;
namespace {

using operator_hub::OperatorPanelCommand;
using operator_hub::OperatorPanelState;
using std::chrono::milliseconds;
using std::chrono::seconds;

// Generous: sanitizer builds on a loaded 2-core machine; the test checks behaviour, not timing.
constexpr auto kPatience = seconds(20);
const std::string kOperatorDir = HUBRT_OPERATOR_HUB_DIR;

// The shipped hub file with the test allow-list (absolute: the copy lives elsewhere).
std::string test_hub_file() {
  std::ifstream in(kOperatorDir + "/operator_hub.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "allow_list: operators.list";
  text.replace(text.find(from), from.size(), "allow_list: " + kOperatorDir + "/test/operators.list");
  const auto path = std::filesystem::path(::testing::TempDir()) / "serve-operator_hub.yaml";
  std::ofstream(path) << text;
  return path.string();
}

class HubctlServeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "test-planner");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    auto command_topic = dds::Topic<OperatorPanelCommand>::create(*participant_, "/operator_panel/command");
    ASSERT_TRUE(command_topic) << command_topic.error().message;
    command_topic_.emplace(std::move(*command_topic));
    auto writer = dds::Writer<OperatorPanelCommand>::create(*participant_, *command_topic_);
    ASSERT_TRUE(writer) << writer.error().message;
    command_writer_.emplace(std::move(*writer));
    auto state_topic = dds::Topic<OperatorPanelState>::create(*participant_, "/operator_hub/panel/state");
    ASSERT_TRUE(state_topic) << state_topic.error().message;
    state_topic_.emplace(std::move(*state_topic));
    auto reader = dds::Reader<OperatorPanelState>::create(*participant_, *state_topic_);
    ASSERT_TRUE(reader) << reader.error().message;
    state_reader_.emplace(std::move(*reader));

    HubProcessOptions options;
    options.board = kOperatorDir + "/../../boards/host-sim-operator-hub.yaml";
    options.hub = test_hub_file();
    auto hub = HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(command_writer_->wait_for_readers(1, kPatience)) << hub_->output();

    // The planner wants an operator: "verify", repeated every 50 ms (the hub's timeout is 1 s).
    planner_ = std::thread([this] {
      while (!stop_.load()) {
        hub_msgs::OperatorPanelCommand c;
        c.set_target_type("operator_panel");
        c.set_target_name("panel");
        c.set_action("verify");
        if (!command_writer_->write(c.wire()).is_ok()) return;
        std::this_thread::sleep_for(milliseconds(50));
      }
    });

    auto serve = test_support::ChildProcess::start(
        HUBRT_HUBCTL_PATH,
        {"serve", "--listen", "127.0.0.1:0", "--operator-state", "/operator_hub/panel/state"},
        domain_->env());
    ASSERT_TRUE(serve) << serve.error().message;
    serve_.emplace(std::move(*serve));
    ASSERT_TRUE(serve_->wait_for_output("serving http://127.0.0.1:", kPatience)) << serve_->stderr_text();
    const std::string out = serve_->stdout_text();
    const auto at = out.find("127.0.0.1:") + 10;
    port_ = std::stoi(out.substr(at, out.find('/', at) - at));
    ASSERT_GT(port_, 0);
  }

  void TearDown() override {
    stop_.store(true);
    if (planner_.joinable()) planner_.join();
  }

  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(10, 0);
    c.set_connection_timeout(5, 0);
    return c;
  }

  // The last State with confirm_seq and the operator (taking everything pending).
  OperatorPanelState latest() {
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    bool any = false;
    while (std::chrono::steady_clock::now() < deadline) {
      const Result<bool> taken = state_reader_->take_next(state_);
      if (taken.is_ok() && taken.value()) {
        any = true;
        continue;
      }
      if (any) break;
      std::this_thread::sleep_for(milliseconds(5));
    }
    return state_.get();
  }

  bool wait_for_state(const std::function<bool(hub_msgs::OperatorPanelStateView)>& predicate) {
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    while (std::chrono::steady_clock::now() < deadline) {
      const Result<bool> taken = state_reader_->take_next(state_);
      if (taken.is_ok() && taken.value()) {
        if (predicate(hub_msgs::OperatorPanelStateView(state_.get()))) return true;
        continue;
      }
      std::this_thread::sleep_for(milliseconds(2));
    }
    return false;
  }

  // POST /confirm as the page does it (its header), or without it.
  httplib::Result press(bool with_header = true) {
    httplib::Headers headers;
    if (with_header) headers.emplace("X-Hubrt-Screen", "confirm");
    return client().Post("/confirm", headers, std::string(), "text/plain");
  }

  void show_badge(std::string_view text) {
    auto send =
        test_support::ChildProcess::start(HUBRT_HUBCTL_PATH,
                                          {"send", "/sim/badge", "hub=operator_hub", "reader=operator_rfid",
                                           "text=" + std::string(text), "--once", "--wait", "1", "--quiet"},
                                          domain_->env());
    ASSERT_TRUE(send) << send.error().message;
    auto status = send->wait(kPatience);
    ASSERT_TRUE(status) << status.error().message;
    ASSERT_TRUE(status->exited_with(0)) << status->describe() << "\n" << send->stderr_text();
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<OperatorPanelCommand>> command_topic_;
  std::optional<dds::Writer<OperatorPanelCommand>> command_writer_;
  std::optional<dds::Topic<OperatorPanelState>> state_topic_;
  std::optional<dds::Reader<OperatorPanelState>> state_reader_;
  dds::Sample<OperatorPanelState> state_;
  std::optional<HubProcess> hub_;
  std::optional<test_support::ChildProcess> serve_;
  std::atomic<bool> stop_{false};
  std::thread planner_;
  int port_ = 0;
};

TEST_F(HubctlServeTest, PageEventsAndTheConfirmRule) {
  // The page, with its security headers.
  auto page = client().Get("/");
  ASSERT_TRUE(page) << httplib::to_string(page.error());
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("id=\"done\""), std::string::npos);
  EXPECT_NE(page->get_header_value("Content-Security-Policy").find("default-src 'none'"), std::string::npos);
  EXPECT_EQ(client().Get("/screen.js")->status, 200);
  EXPECT_EQ(client().Get("/nothing")->status, 404);

  // The server has found the panel, fresh, with the planner's verify in force and nobody verified.
  ASSERT_TRUE(wait_for_state([](auto s) { return s.fresh_msg() && s.reader_open(); })) << hub_->output();
  const auto found_deadline = std::chrono::steady_clock::now() + kPatience;
  std::string state_json;
  while (std::chrono::steady_clock::now() < found_deadline) {
    state_json = client().Get("/state")->body;
    if (state_json.find("\"topic\":\"/operator_hub/panel/state\",\"fresh\":true") != std::string::npos) break;
    std::this_thread::sleep_for(milliseconds(100));
  }
  ASSERT_NE(state_json.find("\"fresh\":true"), std::string::npos) << state_json;

  // No verified operator: 409, and the hub counts nothing.
  auto refused = press();
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 409) << refused->body;
  EXPECT_NE(refused->body.find("no operator is verified"), std::string::npos) << refused->body;
  std::this_thread::sleep_for(milliseconds(1500));  // time for a press that should not exist
  EXPECT_EQ(hub_msgs::OperatorPanelStateView(latest()).confirm_seq(), 0U);

  // Server-sent events: a badge verifies Anna and the stream says so.
  std::mutex mutex;
  std::string stream;
  bool seen = false;
  std::thread events([&] {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(30, 0);
    c.Get("/events", [&](const char* data, std::size_t length) {
      const std::lock_guard<std::mutex> lock(mutex);
      stream.append(data, length);
      seen = stream.find("\"verified\":true,\"name\":\"Anna Svensson\"") != std::string::npos;
      return !seen && stream.size() < 4'000'000;
    });
  });
  std::this_thread::sleep_for(milliseconds(300));  // the stream is open before the badge
  show_badge("0004123456");
  events.join();
  {
    const std::lock_guard<std::mutex> lock(mutex);
    EXPECT_TRUE(seen) << stream.substr(0, 2000);
    EXPECT_EQ(stream.rfind("event: state\ndata: {", 0), 0U) << stream.substr(0, 200);
  }

  // Guards: not the page's request, another Host.
  auto no_header = press(false);
  ASSERT_TRUE(no_header);
  EXPECT_EQ(no_header->status, 403);
  httplib::Headers rebinding{{"Host", "evil.example:" + std::to_string(port_)},
                             {"X-Hubrt-Screen", "confirm"}};
  auto foreign = client().Post("/confirm", rebinding, std::string(), "text/plain");
  ASSERT_TRUE(foreign);
  EXPECT_EQ(foreign->status, 403);

  // Verified: accepted, and the hub's sequence grows by one, from the screen.
  auto accepted = press();
  ASSERT_TRUE(accepted);
  EXPECT_EQ(accepted->status, 200) << accepted->body;
  ASSERT_TRUE(wait_for_state([](auto s) { return s.confirm_seq() == 1; })) << hub_->output();
  EXPECT_EQ(hub_msgs::OperatorPanelStateView(state_.get()).confirm_source(), "screen");
  // A second press within the interval (1 s) is refused; the machine is slow, so only when the
  // answer came back in time to be "too soon" can this be asserted.
  const auto before = std::chrono::steady_clock::now();
  auto again = press();
  ASSERT_TRUE(again);
  if (std::chrono::steady_clock::now() - before < milliseconds(500)) {
    EXPECT_EQ(again->status, 429);
  }

  // An oversized body is refused before any handler.
  auto big =
      client().Post("/confirm", {{"X-Hubrt-Screen", "confirm"}}, std::string(8 * 1024, 'x'), "text/plain");
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413);

  ASSERT_TRUE(serve_->signal(SIGTERM));
  auto status = serve_->wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << serve_->stderr_text();
}

// The planner's instruction (hubctl play's instruction step) reaches a screen that was already
// open: the new writer waits for the screen discovery knows, so the first instruction is not lost.
TEST_F(HubctlServeTest, APlayedInstructionReachesAnOpenScreen) {
  const auto file = std::filesystem::path(::testing::TempDir()) / "instruction.yaml";
  std::ofstream(file) << "steps:\n  - instruction: {step: bolts, text: \"Place the 24 bolts, then press "
                         "done\"}\n";
  auto play = test_support::ChildProcess::start(HUBRT_HUBCTL_PATH, {"play", file.string(), "--timeout", "20"},
                                                domain_->env());
  ASSERT_TRUE(play) << play.error().message;
  auto played = play->wait(kPatience);
  ASSERT_TRUE(played) << played.error().message;
  EXPECT_TRUE(played->exited_with(0)) << play->stdout_text() << play->stderr_text();
  const auto deadline = std::chrono::steady_clock::now() + kPatience;
  std::string state_json;
  while (std::chrono::steady_clock::now() < deadline) {
    state_json = client().Get("/state")->body;
    if (state_json.find("\"step\":\"bolts\"") != std::string::npos) break;
    std::this_thread::sleep_for(milliseconds(100));
  }
  EXPECT_NE(state_json.find("\"text\":\"Place the 24 bolts, then press done\""), std::string::npos)
      << state_json;
}

// hubctl watch shares the screen's discovery and freshness (station_watch): it still finds the
// operator panel's State and shows it operational and fresh.
TEST_F(HubctlServeTest, WatchSeesTheSameStation) {
  auto watch = test_support::ChildProcess::start(HUBRT_HUBCTL_PATH, {"watch", "--plain", "--duration", "4"},
                                                 domain_->env());
  ASSERT_TRUE(watch) << watch.error().message;
  auto status = watch->wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << watch->stderr_text();
  const std::string out = watch->stdout_text();
  EXPECT_NE(out.find("/operator_hub/panel/state"), std::string::npos) << out;
  EXPECT_NE(out.find("operational"), std::string::npos) << out;
  EXPECT_NE(out.find("operator_verified: false"), std::string::npos) << out;
}

}  // namespace
}  // namespace hubrt::integration
