// The bridge between the tap and the clients, without sockets or DDS: every client first gets
// "Server Info" and one "Advertise" of what is there; topics that come and go are advertised and
// unadvertised (the same id again); samples reach the clients subscribed to their channel; a client
// that never reads loses its own samples while another gets all of them, also with the tap's
// events coming from another thread; places are bounded; who may publish is decided per client.
#include "foxglove_bridge.h"

#include <atomic>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace hubrt::hubctl::foxglove {
namespace {

using nlohmann::json;

const Time kBridgeStart = Time(std::chrono::seconds(1000));

struct FakeLink final : ClientLink {
  std::atomic<int> wakes{0};
  std::atomic<int> closes{0};
  void wake() noexcept override { ++wakes; }
  void close() noexcept override { ++closes; }
};

std::shared_ptr<const TapTopic> topic_of(std::uint32_t id, const std::string& name,
                                         std::string schema = "bool x") {
  auto topic = std::make_shared<TapTopic>();
  topic->id = id;
  topic->ros_name = name;
  topic->type_name = "hub_msgs/msg/DockState";
  topic->schema = std::move(schema);
  return topic;
}

TapEvent event(TapEvent::Kind kind, std::shared_ptr<const TapTopic> topic, std::size_t bytes = 10) {
  TapEvent e{kind, topic, nullptr};
  if (kind == TapEvent::Kind::kSample) {
    auto sample = std::make_shared<TapSample>();
    sample->topic = topic;
    sample->cdr.assign(bytes, 1);
    e.sample = std::move(sample);
  }
  return e;
}

std::vector<json> texts(ClientSession& session, std::size_t* binary = nullptr) {
  std::vector<json> out;
  while (auto frame = session.next_frame()) {
    if (frame->is_text()) {
      out.push_back(json::parse(*frame->text));
    } else if (binary != nullptr) {
      ++*binary;
    }
  }
  return out;
}

class BridgeTest : public ::testing::Test {
 protected:
  std::shared_ptr<ClientSession> join(Bridge& bridge, const std::string& origin = {}) {
    links_.push_back(std::make_shared<FakeLink>());
    EXPECT_TRUE(bridge.reserve());
    return bridge.connect("127.0.0.1:1", origin, links_.back());
  }
  BridgeOptions options_;
  std::vector<std::shared_ptr<FakeLink>> links_;
};

TEST_F(BridgeTest, ServerInfoThenOneAdvertiseOfWhatIsThere) {
  Bridge bridge(options_, nullptr, {});
  auto early = join(bridge);
  auto frames = texts(*early);
  ASSERT_EQ(frames.size(), 2U);
  EXPECT_EQ(frames[0]["op"], "serverInfo");
  EXPECT_EQ(frames[1], json({{"op", "advertise"}, {"channels", json::array()}}));  // "at least one"
  EXPECT_EQ(links_[0]->wakes, 1);

  bridge.dispatch(event(TapEvent::Kind::kTopic, topic_of(0, "/diagnostics")));
  bridge.dispatch(event(TapEvent::Kind::kTopic, topic_of(4, "/dock_ecu/dock/state")));
  bridge.dispatch(event(TapEvent::Kind::kTopic, topic_of(5, "/unknown", "")));  // no schema: not offered
  auto late = join(bridge);
  frames = texts(*late);
  ASSERT_EQ(frames.size(), 2U);
  ASSERT_EQ(frames[1]["channels"].size(), 2U);
  EXPECT_EQ(frames[1]["channels"][0]["topic"], "/diagnostics");
  EXPECT_EQ(frames[1]["channels"][1]["id"], 4);
  EXPECT_EQ(texts(*early).size(), 2U);  // the earlier client got each as it came
  EXPECT_EQ(bridge.counters().channels, 2U);
}

TEST_F(BridgeTest, ChannelsFollowTheTopicsAsTheyComeAndGo) {
  Bridge bridge(options_, nullptr, {});
  auto client = join(bridge);
  texts(*client);
  const auto state = topic_of(2, "/tool_ecu/lift/state");
  bridge.dispatch(event(TapEvent::Kind::kTopic, state));
  auto revised = std::make_shared<TapTopic>(*state);
  revised->revision = 1;  // another writer's QoS: the same channel, nothing to say
  bridge.dispatch(event(TapEvent::Kind::kTopic, revised));
  client->on_text(R"({"op":"subscribe","subscriptions":[{"id":7,"channelId":2}]})", kBridgeStart);
  bridge.dispatch(event(TapEvent::Kind::kSample, state));
  bridge.dispatch(event(TapEvent::Kind::kTopicGone, state));
  bridge.dispatch(event(TapEvent::Kind::kSample, state));  // after gone: nobody gets it
  bridge.dispatch(event(TapEvent::Kind::kTopic, state));
  std::size_t binary = 0;
  auto frames = texts(*client, &binary);
  ASSERT_EQ(frames.size(), 3U);
  EXPECT_EQ(frames[0]["op"], "advertise");
  EXPECT_EQ(frames[1], json({{"op", "unadvertise"}, {"channelIds", {2}}}));
  EXPECT_EQ(frames[2]["op"], "advertise");
  EXPECT_EQ(frames[2]["channels"][0]["id"], 2);  // same topic, same schema: the same id
  EXPECT_EQ(binary, 1U);
}

TEST_F(BridgeTest, AClientThatNeverReadsLosesOnlyItsOwnSamples) {
  options_.limits.data_bytes = 10 * (13 + 100);
  Bridge bridge(options_, nullptr, {});
  const auto state = topic_of(1, "/dock_ecu/dock/state");
  bridge.dispatch(event(TapEvent::Kind::kTopic, state));
  auto reader = join(bridge);
  auto stalled = join(bridge);
  for (auto* client : {&reader, &stalled})
    (*client)->on_text(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1}]})", kBridgeStart);
  texts(*reader);
  // The tap's events from another thread, as in hubctl; this thread reads for one client only.
  constexpr std::size_t kSamples = 2000;
  std::atomic<bool> done{false};
  std::thread dispatcher([&] {
    for (std::size_t i = 0; i < kSamples; ++i) {
      bridge.dispatch(event(TapEvent::Kind::kSample, state, 100));
      if (i % 200 == 0) std::this_thread::yield();
    }
    done = true;
  });
  std::size_t received = 0;
  while (!done || reader->queued_bytes() > 0) {
    if (auto frame = reader->next_frame(); frame && !frame->is_text()) ++received;
  }
  dispatcher.join();
  bridge.tick(kBridgeStart);
  EXPECT_EQ(received + reader->counters().messages_dropped, kSamples);
  EXPECT_EQ(stalled->counters().messages_queued, 10U);
  EXPECT_EQ(stalled->counters().messages_dropped, kSamples - 10);
  // The reader kept up at least as well as the stalled one, which cost it nothing.
  EXPECT_GE(received, 10U);
  std::size_t binary = 0;
  auto frames = texts(*stalled, &binary);
  EXPECT_EQ(binary, 10U);
  ASSERT_FALSE(frames.empty());
  EXPECT_EQ(frames.back()["message"], "Send buffer limit reached");
}

TEST_F(BridgeTest, PlacesAreBoundedAndGivenBack) {
  options_.max_clients = 2;
  Bridge bridge(options_, nullptr, {});
  auto first = join(bridge);
  EXPECT_TRUE(bridge.reserve());
  EXPECT_FALSE(bridge.reserve());  // one client and one held place
  bridge.release();
  EXPECT_TRUE(bridge.reserve());
  bridge.release();
  bridge.disconnect(first->id());
  EXPECT_TRUE(bridge.reserve());
  EXPECT_TRUE(bridge.reserve());
  EXPECT_FALSE(bridge.reserve());
  EXPECT_EQ(bridge.counters().refused_clients, 2U);
}

struct NoSink final : CommandSink {
  Expected<std::shared_ptr<CommandWriter>> open(const std::string&, std::string_view) override {
    return make_error(ErrorCode::kInternal, "not in this test");
  }
};

TEST_F(BridgeTest, WhoMayPublishIsDecidedPerClient) {
  NoSink sink;
  const auto capabilities = [](ClientSession& session) { return texts(session).at(0)["capabilities"]; };
  {
    Bridge off(options_, &sink, {});
    EXPECT_EQ(capabilities(*join(off)), json::array());
  }
  options_.allow_publish = true;
  options_.publish_origins = {"https://app.foxglove.dev"};
  std::vector<std::string> log;
  Bridge on(options_, &sink, [&log](std::string_view line) { log.emplace_back(line); });
  EXPECT_EQ(capabilities(*join(on)), json::array({"clientPublish"}));  // no Origin: not a web page
  EXPECT_EQ(capabilities(*join(on, "https://app.foxglove.dev")), json::array({"clientPublish"}));
  auto page = join(on, "https://evil.example");
  EXPECT_EQ(capabilities(*page), json::array());
  page->on_text(
      R"({"op":"advertise","channels":[{"id":1,"topic":"/dock/command","encoding":"cdr","schemaName":"x"}]})",
      kBridgeStart);
  const std::string refusal = texts(*page).at(0)["message"];
  EXPECT_NE(refusal.find("pages from https://evil.example may not publish"), std::string::npos) << refusal;
  EXPECT_NE(log.back().find("pages from https://evil.example"), std::string::npos);
}

TEST_F(BridgeTest, AClientThatReadsNoJsonIsClosed) {
  options_.limits.control_bytes = 200;
  Bridge bridge(options_, nullptr, {});
  auto client = join(bridge);
  bridge.tick(kBridgeStart);
  EXPECT_EQ(links_[0]->closes, 0);
  for (std::uint32_t id = 0; id < 10; ++id)
    bridge.dispatch(event(TapEvent::Kind::kTopic, topic_of(id, "/t")));
  bridge.tick(kBridgeStart);
  EXPECT_EQ(links_[0]->closes, 1);
}

}  // namespace
}  // namespace hubrt::hubctl::foxglove
