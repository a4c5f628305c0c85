// One Foxglove client's session, without a socket: subscriptions as the spec has them, a slow
// client's queue bounded in bytes with its drops counted and reported (one status at a time, a log
// line at most every 10 s), JSON never dropped, and publishing only when allowed, only on command
// topics, within a budget, through the sink — whose refusals reach the client. Time is passed in.
#include "foxglove_session.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace hubrt::hubctl::foxglove {
namespace {

using nlohmann::json;
using std::chrono::milliseconds;

const Time kStart = Time(std::chrono::seconds(1000));

struct FakeWriter final : CommandWriter {
  std::vector<std::vector<std::uint8_t>> written;
  Status write(std::span<const std::uint8_t> cdr) noexcept override {
    if (!cdr.empty() && cdr[0] == 0xFF) return Status(ErrorCode::kInvalidArgument);  // "does not deserialize"
    written.emplace_back(cdr.begin(), cdr.end());
    return Status::ok();
  }
};

struct FakeSink final : CommandSink {
  std::shared_ptr<FakeWriter> writer = std::make_shared<FakeWriter>();
  std::vector<std::pair<std::string, std::string>> opened;
  Expected<std::shared_ptr<CommandWriter>> open(const std::string& topic,
                                                std::string_view schema_name) override {
    opened.emplace_back(topic, schema_name);
    if (schema_name != "hub_msgs/msg/DockCommand")
      return make_error(ErrorCode::kInvalidArgument, "not a command type");
    return std::shared_ptr<CommandWriter>(writer);
  }
};

std::shared_ptr<const TapSample> sample_of(std::size_t bytes, std::int64_t receive_ns = 5) {
  auto sample = std::make_shared<TapSample>();
  sample->receive_time.ns_since_epoch = receive_ns;
  sample->cdr.assign(bytes, 0x42);
  return sample;
}

class SessionTest : public ::testing::Test {
 protected:
  std::unique_ptr<ClientSession> make(PublishPermission publish = {false, "publishing is off"}) {
    return std::make_unique<ClientSession>(1, "peer", limits_, std::move(publish), &sink_,
                                           [this](std::string_view line) { log_.emplace_back(line); });
  }
  // Every frame queued now, in order.
  static std::vector<OutFrame> drain(ClientSession& session) {
    std::vector<OutFrame> frames;
    while (auto frame = session.next_frame()) frames.push_back(std::move(*frame));
    return frames;
  }
  static std::vector<json> texts(ClientSession& session) {
    std::vector<json> out;
    for (const OutFrame& frame : drain(session)) {
      if (frame.is_text()) out.push_back(json::parse(*frame.text));
    }
    return out;
  }
  static void advertise(ClientSession& session, std::initializer_list<std::uint32_t> ids) {
    const std::vector<std::uint32_t> list(ids);
    session.channels_added(list, std::make_shared<const std::string>("{\"op\":\"advertise\"}"));
  }

  SessionLimits limits_;
  FakeSink sink_;
  std::vector<std::string> log_;
};

TEST(FoxgloveCommandTopic, OnlyCommandTopicsOfEitherLayout) {
  for (const char* yes : {"/dock/command", "/tool_ecu/command", "/station1/lift/command", "/_x/command"})
    EXPECT_TRUE(is_command_topic(yes)) << yes;
  for (const char* no :
       {"/command", "command", "/dock_ecu/dock/state", "/diagnostics", "/dock/command/x", "/dock//command",
        "//command", "/1dock/command", "/do-ck/command", "/dock/commands", "/dock/ command"})
    EXPECT_FALSE(is_command_topic(no)) << no;
}

TEST(FoxgloveRateBudget, RefillsWithTimeUpToTheBurst) {
  RateBudget budget(10, 3);
  EXPECT_TRUE(budget.take(kStart));
  EXPECT_TRUE(budget.take(kStart));
  EXPECT_TRUE(budget.take(kStart));
  EXPECT_FALSE(budget.take(kStart));
  EXPECT_TRUE(budget.take(kStart + milliseconds(100)));  // one token in 0.1 s at 10/s
  EXPECT_FALSE(budget.take(kStart + milliseconds(100)));
  EXPECT_FALSE(budget.take(kStart + milliseconds(50)));  // time going back gives nothing
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(budget.take(kStart + std::chrono::seconds(60)));
  EXPECT_FALSE(budget.take(kStart + std::chrono::seconds(60)));  // saved up to the burst only
}

TEST_F(SessionTest, SubscribedSamplesGoOutWithTheirSubscriptionAndReceiveTime) {
  auto session = make();
  advertise(*session, {3, 4});
  EXPECT_FALSE(session->on_text(R"({"op":"subscribe","subscriptions":[{"id":9,"channelId":3}]})", kStart));
  drain(*session);
  const auto sample = sample_of(20, 1'700'000'000'123'456'789);
  EXPECT_TRUE(session->sample(3, sample));   // queue was empty: the connection must be woken
  EXPECT_FALSE(session->sample(4, sample));  // not subscribed: nothing
  EXPECT_FALSE(session->sample(3, sample));  // queued behind the first: no second wake
  auto frames = drain(*session);
  ASSERT_EQ(frames.size(), 2U);
  EXPECT_FALSE(frames[0].is_text());
  EXPECT_EQ(frames[0].header, message_data_header(9, 1'700'000'000'123'456'789ULL));
  EXPECT_EQ(frames[0].sample, sample);  // the tap's bytes themselves, not a copy
  EXPECT_EQ(frames[0].bytes(), 13U + 20U);
  EXPECT_EQ(session->counters().messages_dropped, 0U);
}

TEST_F(SessionTest, SubscribeErrorsFollowTheSpec) {
  limits_.max_subscriptions = 2;
  auto session = make();
  advertise(*session, {1, 2, 3});
  session->on_text(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1}]})", kStart);
  session->on_text(R"({"op":"subscribe","subscriptions":[{"id":2,"channelId":8},{"id":1,"channelId":2},)"
                   R"({"id":3,"channelId":1},{"id":4,"channelId":2},{"id":5,"channelId":3}]})",
                   kStart);
  auto statuses = texts(*session);
  ASSERT_EQ(statuses.size(), 2U);  // the advertise, then one status for the whole request
  const std::string message = statuses[1]["message"];
  EXPECT_EQ(statuses[1]["level"], 2);
  EXPECT_NE(message.find("channel 8 is not advertised"), std::string::npos) << message;
  EXPECT_NE(message.find("subscription id 1 is in use"), std::string::npos) << message;
  EXPECT_NE(message.find("channel 1 has subscription 1 already"), std::string::npos) << message;
  EXPECT_NE(message.find("and 1 more"), std::string::npos) << message;  // at most 2: id 5 refused
  // id 4 on channel 2 was taken (the second of two allowed).
  EXPECT_TRUE(session->sample(2, sample_of(1)));
  EXPECT_FALSE(session->sample(3, sample_of(1)));
}

TEST_F(SessionTest, AFullQueueDropsThisClientsSamplesAndSaysSoOnce) {
  limits_.data_bytes = 3 * (13 + 100);
  auto session = make();
  advertise(*session, {1});
  session->on_text(R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":1}]})", kStart);
  for (int i = 0; i < 10; ++i) session->sample(1, sample_of(100));
  EXPECT_EQ(session->counters().messages_queued, 3U);
  EXPECT_EQ(session->counters().messages_dropped, 7U);
  // JSON is never dropped, however full the data queue is.
  session->send_text(
      std::make_shared<const std::string>("{\"op\":\"status\",\"level\":0,\"message\":\"x\"}"));
  session->report_drops(kStart);
  ASSERT_EQ(log_.size(), 1U);
  EXPECT_NE(log_[0].find("7 messages dropped so far (+7)"), std::string::npos) << log_[0];
  // More drops while the warning still waits: no second warning, no log line within 10 s.
  session->sample(1, sample_of(100));
  session->report_drops(kStart + std::chrono::seconds(1));
  EXPECT_EQ(log_.size(), 1U);
  auto frames = drain(*session);
  int warnings = 0;
  for (const OutFrame& frame : frames) {
    if (!frame.is_text()) continue;
    const json status = json::parse(*frame.text);
    if (status.value("id", "") == "hubctl-send-buffer") {
      ++warnings;
      EXPECT_EQ(status["message"], "Send buffer limit reached");
      EXPECT_EQ(status["level"], 1);
    }
  }
  EXPECT_EQ(warnings, 1);
  EXPECT_EQ(frames.size(), 3U + 1U + 1U + 1U);  // 3 samples, the advertise, the status, the warning
  // Sent: the next drops get a warning again, and after 10 s a log line.
  for (int i = 0; i < 5; ++i) session->sample(1, sample_of(100));
  session->report_drops(kStart + std::chrono::seconds(11));
  ASSERT_EQ(log_.size(), 2U);
  EXPECT_NE(log_[1].find("10 messages dropped so far (+3)"), std::string::npos) << log_[1];
  EXPECT_EQ(session->counters().messages_dropped, 10U);
}

TEST_F(SessionTest, AClientThatReadsNoJsonIsOverloaded) {
  limits_.control_bytes = 100;
  auto session = make();
  EXPECT_FALSE(session->overloaded());
  session->send_text(std::make_shared<const std::string>(std::string(101, ' ')));
  EXPECT_TRUE(session->overloaded());
  drain(*session);
  EXPECT_FALSE(session->overloaded());
}

TEST_F(SessionTest, AChannelGoneEndsItsSubscriptionQuietly) {
  auto session = make();
  advertise(*session, {1});
  session->on_text(R"({"op":"subscribe","subscriptions":[{"id":5,"channelId":1}]})", kStart);
  session->sample(1, sample_of(10));
  session->channel_removed(1, std::make_shared<const std::string>("{\"op\":\"unadvertise\"}"));
  EXPECT_FALSE(session->sample(1, sample_of(10)));
  auto frames = drain(*session);
  ASSERT_EQ(frames.size(), 3U);  // advertise, the sample queued before, then the unadvertise
  EXPECT_FALSE(frames[1].is_text());
  EXPECT_TRUE(frames[2].is_text());
  // Foxglove unsubscribes what an unadvertise ended: no error. An unknown id is one.
  session->on_text(R"({"op":"unsubscribe","subscriptionIds":[5]})", kStart);
  EXPECT_TRUE(texts(*session).empty());
  session->on_text(R"({"op":"unsubscribe","subscriptionIds":[5]})", kStart);
  auto statuses = texts(*session);
  ASSERT_EQ(statuses.size(), 1U);
  EXPECT_EQ(statuses[0]["message"], "unsubscribe: no subscription 5");
  // The channel back: a subscription may use the id again.
  advertise(*session, {1});
  session->on_text(R"({"op":"subscribe","subscriptions":[{"id":5,"channelId":1}]})", kStart);
  EXPECT_EQ(texts(*session).size(), 1U);  // the advertise only
  EXPECT_TRUE(session->sample(1, sample_of(10)));
}

TEST_F(SessionTest, UnsubscribingDropsWhatWasQueuedForIt) {
  auto session = make();
  advertise(*session, {1, 2});
  session->on_text(R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1},{"id":2,"channelId":2}]})",
                   kStart);
  drain(*session);
  session->sample(1, sample_of(10));
  session->sample(2, sample_of(10));
  session->sample(1, sample_of(10));
  session->on_text(R"({"op":"unsubscribe","subscriptionIds":[1]})", kStart);
  auto frames = drain(*session);
  ASSERT_EQ(frames.size(), 1U);
  EXPECT_EQ(frames[0].subscription_id, 2U);
  EXPECT_EQ(session->queued_bytes(), 0U);
}

TEST_F(SessionTest, MalformedAndUnofferedRequestsGetErrors) {
  limits_.requests_per_s = 3;
  auto session = make();
  session->on_text("not json", kStart);
  session->on_text(R"({"op":"setParameters","parameters":[]})", kStart);
  session->on_text(R"({"op":"unsubscribe","subscriptionIds":[]})", kStart);
  session->on_text(R"({"op":"unsubscribe","subscriptionIds":[]})", kStart);  // 4th in the same instant
  session->on_text(R"({"op":"unsubscribe","subscriptionIds":[]})", kStart);  // throttled: no 2nd warning
  auto statuses = texts(*session);
  ASSERT_EQ(statuses.size(), 3U);
  EXPECT_NE(statuses[0]["message"].get<std::string>().find("not JSON"), std::string::npos);
  EXPECT_NE(statuses[1]["message"].get<std::string>().find("\"setParameters\" is not offered"),
            std::string::npos);
  EXPECT_NE(statuses[2]["message"].get<std::string>().find("too many requests"), std::string::npos);
  session->on_text(R"({"op":"unsubscribe","subscriptionIds":[]})", kStart + std::chrono::seconds(1));
  EXPECT_TRUE(texts(*session).empty());  // budget back
}

TEST_F(SessionTest, PublishingOffRefusesAndWritesNothing) {
  auto session = make({false, "publishing is off: hubctl foxglove runs without --allow-publish"});
  session->on_text(
      R"({"op":"advertise","channels":[{"id":1,"topic":"/dock/command","encoding":"cdr","schemaName":"hub_msgs/msg/DockCommand"}]})",
      kStart);
  const std::uint8_t frame[] = {0x01, 0x01, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00};
  session->on_binary(frame, kStart);
  session->on_binary(frame, kStart + milliseconds(10));  // within the second: counted, no 2nd status
  auto statuses = texts(*session);
  ASSERT_EQ(statuses.size(), 2U);
  EXPECT_NE(statuses[0]["message"].get<std::string>().find("advertise refused"), std::string::npos);
  EXPECT_NE(statuses[0]["message"].get<std::string>().find("without --allow-publish"), std::string::npos);
  EXPECT_NE(statuses[1]["message"].get<std::string>().find("message not written"), std::string::npos);
  EXPECT_TRUE(sink_.opened.empty());
  EXPECT_TRUE(sink_.writer->written.empty());
  EXPECT_EQ(session->counters().publish_refused, 2U);
}

TEST_F(SessionTest, PublishesOnlyCdrOnCommandTopicsThroughTheSink) {
  limits_.publish_per_s = 2;
  auto session = make({true, {}});
  session->on_text(
      R"({"op":"advertise","channels":[)"
      R"({"id":1,"topic":"/dock/command","encoding":"cdr","schemaName":"hub_msgs/msg/DockCommand"},)"
      R"({"id":2,"topic":"/dock_ecu/dock/state","encoding":"cdr","schemaName":"hub_msgs/msg/DockCommand"},)"
      R"({"id":3,"topic":"/dock/command","encoding":"json","schemaName":"hub_msgs/msg/DockCommand"},)"
      R"({"id":4,"topic":"/lift/command","encoding":"cdr","schemaName":"hub_msgs/msg/DockState"}]})",
      kStart);
  auto statuses = texts(*session);
  ASSERT_EQ(statuses.size(), 1U);
  const std::string refused = statuses[0]["message"];
  EXPECT_NE(
      refused.find("channel 2 on /dock_ecu/dock/state: \"/dock_ecu/dock/state\" is not a command topic"),
      std::string::npos)
      << refused;
  EXPECT_NE(refused.find("encoding \"json\""), std::string::npos) << refused;
  EXPECT_NE(refused.find("channel 4 on /lift/command: not a command type"), std::string::npos) << refused;
  // The sink was asked for the command topics only.
  ASSERT_EQ(sink_.opened.size(), 2U);
  EXPECT_EQ(sink_.opened[0],
            (std::pair<std::string, std::string>{"/dock/command", "hub_msgs/msg/DockCommand"}));

  const std::uint8_t good[] = {0x01, 0x01, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x07};
  const std::uint8_t bad[] = {0x01, 0x01, 0x00, 0x00, 0x00, 0xFF};
  const std::uint8_t unknown[] = {0x01, 0x02, 0x00, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00};
  session->on_binary(good, kStart);
  ASSERT_EQ(sink_.writer->written.size(), 1U);
  EXPECT_EQ(sink_.writer->written[0], (std::vector<std::uint8_t>{0x00, 0x01, 0x00, 0x00, 0x07}));
  session->on_binary(bad, kStart + milliseconds(1));
  session->on_binary(unknown, kStart + milliseconds(2));
  session->on_binary(good, kStart + milliseconds(3));  // past 2 a second: refused
  EXPECT_EQ(sink_.writer->written.size(), 1U);
  statuses = texts(*session);
  ASSERT_EQ(statuses.size(), 3U);
  EXPECT_NE(statuses[0]["message"].get<std::string>().find("does not deserialize"), std::string::npos);
  EXPECT_NE(statuses[1]["message"].get<std::string>().find("which this client has not advertised"),
            std::string::npos);
  EXPECT_NE(statuses[2]["message"].get<std::string>().find("more than 2 messages a second"),
            std::string::npos);
  session->on_binary(good, kStart + std::chrono::seconds(1));
  EXPECT_EQ(sink_.writer->written.size(), 2U);
  EXPECT_EQ(session->counters().published, 2U);
  EXPECT_EQ(session->counters().publish_refused, 3U);
  // Unadvertised: its messages are refused.
  session->on_text(R"({"op":"unadvertise","channelIds":[1]})", kStart + std::chrono::seconds(2));
  session->on_binary(good, kStart + std::chrono::seconds(2));
  EXPECT_EQ(sink_.writer->written.size(), 2U);
}

TEST_F(SessionTest, AClientAdvertisesABoundedNumberOfChannels) {
  limits_.max_client_channels = 1;
  auto session = make({true, {}});
  session->on_text(
      R"({"op":"advertise","channels":[)"
      R"({"id":1,"topic":"/dock/command","encoding":"cdr","schemaName":"hub_msgs/msg/DockCommand"},)"
      R"({"id":1,"topic":"/dock/command","encoding":"cdr","schemaName":"hub_msgs/msg/DockCommand"},)"
      R"({"id":2,"topic":"/dock/command","encoding":"cdr","schemaName":"hub_msgs/msg/DockCommand"}]})",
      kStart);
  auto statuses = texts(*session);
  ASSERT_EQ(statuses.size(), 1U);
  EXPECT_NE(statuses[0]["message"].get<std::string>().find("channel id 1 is in use"), std::string::npos);
  EXPECT_NE(statuses[0]["message"].get<std::string>().find("at most 1 channels per client"),
            std::string::npos);
}

}  // namespace
}  // namespace hubrt::hubctl::foxglove
