// The Foxglove WebSocket protocol's messages as hubctl foxglove writes and reads them (spec:
// foxglove/ws-protocol docs/spec.md): the server's JSON has the spec's fields, Message Data's
// header is little-endian, and every way a client's message can break the spec or the bounds is
// refused with a message that says where.
#include "foxglove_protocol.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace hubrt::hubctl::foxglove {
namespace {

using nlohmann::json;

TEST(FoxgloveProtocol, ServerInfoDeclaresPublishingOnlyWhenAllowed) {
  ServerInfo info{"hubrt hubctl foxglove", false, {{"ROS_DISTRO", "humble"}}, "42"};
  json plain = json::parse(server_info_json(info));
  EXPECT_EQ(plain["op"], "serverInfo");
  EXPECT_EQ(plain["name"], "hubrt hubctl foxglove");
  EXPECT_EQ(plain["capabilities"], json::array());
  EXPECT_FALSE(plain.contains("supportedEncodings"));  // "Only set if client publishing ... supported"
  EXPECT_EQ(plain["metadata"]["ROS_DISTRO"], "humble");
  EXPECT_EQ(plain["sessionId"], "42");
  info.client_publish = true;
  json publishing = json::parse(server_info_json(info));
  EXPECT_EQ(publishing["capabilities"], json::array({"clientPublish"}));
  EXPECT_EQ(publishing["supportedEncodings"], json::array({"cdr"}));
}

TEST(FoxgloveProtocol, StatusHasLevelMessageAndOptionalId) {
  json error = json::parse(status_json(StatusLevel::kError, "no such channel"));
  EXPECT_EQ(error, json({{"op", "status"}, {"level", 2}, {"message", "no such channel"}}));
  json warning = json::parse(status_json(StatusLevel::kWarning, "behind", "drops"));
  EXPECT_EQ(warning["level"], 1);
  EXPECT_EQ(warning["id"], "drops");
  // A name off the wire that is not UTF-8 is replaced, not sent (and dump() does not throw).
  json odd = json::parse(status_json(StatusLevel::kInfo, std::string("topic \xff\xfe")));
  EXPECT_EQ(odd["message"], "topic \xEF\xBF\xBD\xEF\xBF\xBD");
}

TEST(FoxgloveProtocol, AdvertiseSaysCdrAndRos2msg) {
  const Channel channels[] = {{3, "/dock_ecu/dock/state", "hub_msgs/msg/DockState", "StateHeader header\n"},
                              {7, "/diagnostics", "diagnostic_msgs/msg/DiagnosticArray", "x"}};
  json advertise = json::parse(advertise_json(channels));
  EXPECT_EQ(advertise["op"], "advertise");
  ASSERT_EQ(advertise["channels"].size(), 2U);
  EXPECT_EQ(advertise["channels"][0], json({{"id", 3},
                                            {"topic", "/dock_ecu/dock/state"},
                                            {"encoding", "cdr"},
                                            {"schemaName", "hub_msgs/msg/DockState"},
                                            {"schema", "StateHeader header\n"},
                                            {"schemaEncoding", "ros2msg"}}));
  EXPECT_EQ(advertise["channels"][1]["id"], 7);
  EXPECT_EQ(json::parse(advertise_json({})), json({{"op", "advertise"}, {"channels", json::array()}}));
  const std::uint32_t gone[] = {3, 7};
  EXPECT_EQ(json::parse(unadvertise_json(gone)), json({{"op", "unadvertise"}, {"channelIds", {3, 7}}}));
}

TEST(FoxgloveProtocol, MessageDataHeaderIsOpcodeThenLittleEndianIdAndTime) {
  const auto header = message_data_header(0x04030201U, 0x0807060504030201ULL);
  const std::array<std::uint8_t, 13> expected = {0x01, 0x01, 0x02, 0x03, 0x04, 0x01, 0x02,
                                                 0x03, 0x04, 0x05, 0x06, 0x07, 0x08};
  EXPECT_EQ(header, expected);
}

TEST(FoxgloveProtocol, ParsesTheFourClientRequests) {
  auto subscribe = parse_client_text(
      R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":3},{"id":4294967295,"channelId":5}]})");
  ASSERT_TRUE(subscribe) << subscribe.error().message;
  const auto& s = std::get<SubscribeRequest>(*subscribe);
  ASSERT_EQ(s.subscriptions.size(), 2U);
  EXPECT_EQ(s.subscriptions[1].id, 4294967295U);
  EXPECT_EQ(s.subscriptions[1].channel_id, 5U);

  auto unsubscribe = parse_client_text(R"({"op":"unsubscribe","subscriptionIds":[0,1]})");
  ASSERT_TRUE(unsubscribe);
  EXPECT_EQ(std::get<UnsubscribeRequest>(*unsubscribe).subscription_ids, (std::vector<std::uint32_t>{0, 1}));

  // The schema a client may add is not read.
  auto advertise = parse_client_text(
      R"({"op":"advertise","channels":[{"id":1,"topic":"/dock/command","encoding":"cdr",)"
      R"("schemaName":"hub_msgs/msg/DockCommand","schema":"ignored","schemaEncoding":"ros2msg"}]})");
  ASSERT_TRUE(advertise) << advertise.error().message;
  const auto& a = std::get<ClientAdvertiseRequest>(*advertise);
  ASSERT_EQ(a.channels.size(), 1U);
  EXPECT_EQ(a.channels[0].topic, "/dock/command");
  EXPECT_EQ(a.channels[0].encoding, "cdr");
  EXPECT_EQ(a.channels[0].schema_name, "hub_msgs/msg/DockCommand");

  auto unadvertise = parse_client_text(R"({"op":"unadvertise","channelIds":[1]})");
  ASSERT_TRUE(unadvertise);
  EXPECT_EQ(std::get<ClientUnadvertiseRequest>(*unadvertise).channel_ids, (std::vector<std::uint32_t>{1}));

  auto parameters = parse_client_text(R"({"op":"getParameters","parameterNames":[]})");
  ASSERT_TRUE(parameters);
  EXPECT_EQ(std::get<UnsupportedRequest>(*parameters).op, "getParameters");
}

// Each malformed message and (part of) the error it must get.
TEST(FoxgloveProtocol, RefusesMalformedTextSayingWhere) {
  const std::pair<std::string, std::string> cases[] = {
      {"{", "not JSON"},
      {"[1,2]", "expected a JSON object"},
      {R"({"subscriptions":[]})", "no \"op\""},
      {R"({"op":7})", "\"op\": expected a string"},
      {R"({"op":"publish"})", "unknown op \"publish\""},
      {R"({"op":"subscribe"})", "subscribe: no \"subscriptions\""},
      {R"({"op":"subscribe","subscriptions":{}})", "subscribe.subscriptions: expected an array"},
      {R"({"op":"subscribe","subscriptions":[3]})", "subscriptions[0]: expected an object"},
      {R"({"op":"subscribe","subscriptions":[{"id":1}]})", "subscriptions[0]: no \"channelId\""},
      {R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})",
       "subscriptions[0].id: expected an unsigned"},
      {R"({"op":"subscribe","subscriptions":[{"id":1.5,"channelId":1}]})",
       "expected an unsigned 32-bit integer"},
      {R"({"op":"subscribe","subscriptions":[{"id":4294967296,"channelId":1}]})",
       "expected an unsigned 32-bit"},
      {R"({"op":"subscribe","subscriptions":[{"id":"1","channelId":1}]})", "expected an unsigned 32-bit"},
      {R"({"op":"unsubscribe","subscriptionIds":[1,"x"]})", "unsubscribe.subscriptionIds[1]"},
      {R"({"op":"advertise","channels":[{"id":1,"topic":2,"encoding":"cdr","schemaName":"x"}]})",
       "channels[0].topic: expected a string"},
      {R"({"op":"unadvertise"})", "unadvertise: no \"channelIds\""},
      {R"({"op":"subscribe","subscriptions":[[[[[[[[[1]]]]]]]]]})", "nested deeper than 8"},
  };
  for (const auto& [text, expected] : cases) {
    auto parsed = parse_client_text(text);
    ASSERT_FALSE(parsed) << text;
    EXPECT_EQ(parsed.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(parsed.error().message.find(expected), std::string::npos)
        << text << " -> " << parsed.error().message << " (expected '" << expected << "')";
  }
}

TEST(FoxgloveProtocol, BoundsWhatOneRequestMayHold) {
  std::string many = R"({"op":"unsubscribe","subscriptionIds":[)";
  for (std::size_t i = 0; i <= kMaxRequestEntries; ++i) many += (i == 0 ? "" : ",") + std::to_string(i);
  many += "]}";
  auto too_many = parse_client_text(many);
  ASSERT_FALSE(too_many);
  EXPECT_NE(too_many.error().message.find("257 entries, at most 256"), std::string::npos);

  const std::string long_topic(kMaxNameBytes + 1, 'a');
  auto too_long = parse_client_text(R"({"op":"advertise","channels":[{"id":1,"topic":")" + long_topic +
                                    R"(","encoding":"cdr","schemaName":"x"}]})");
  ASSERT_FALSE(too_long);
  EXPECT_NE(too_long.error().message.find("257 bytes, at most 256"), std::string::npos);

  std::string huge = R"({"op":"unsubscribe","subscriptionIds":[],"pad":")" +
                     std::string(kMaxClientMessageBytes, ' ') + "\"}";
  auto oversize = parse_client_text(huge);
  ASSERT_FALSE(oversize);
  EXPECT_NE(oversize.error().message.find("at most 65536"), std::string::npos);

  // Invalid UTF-8 inside a string: nlohmann's lexer stops there.
  auto invalid = parse_client_text(
      "{\"op\":\"advertise\",\"channels\":[{\"id\":1,\"topic\":\"/a\xc3\x28\","
      "\"encoding\":\"cdr\",\"schemaName\":\"x\"}]}");
  ASSERT_FALSE(invalid);
  EXPECT_NE(invalid.error().message.find("not JSON"), std::string::npos);
}

TEST(FoxgloveProtocol, ParsesClientMessageData) {
  const std::uint8_t frame[] = {0x01, 0x07, 0x00, 0x00, 0x01, 0x00, 0x01, 0x00, 0x00, 0xAB};
  auto data = parse_client_binary(frame);
  ASSERT_TRUE(data) << data.error().message;
  EXPECT_EQ(data->channel_id, 0x01000007U);
  ASSERT_EQ(data->payload.size(), 5U);
  EXPECT_EQ(data->payload.data(), frame + 5);  // points into the frame: no copy

  const std::uint8_t header_only[] = {0x01, 0x02, 0x00, 0x00, 0x00};
  ASSERT_TRUE(parse_client_binary(header_only));
  EXPECT_TRUE(parse_client_binary(header_only)->payload.empty());
}

TEST(FoxgloveProtocol, RefusesMalformedBinary) {
  const std::vector<std::pair<std::vector<std::uint8_t>, std::string>> cases = {
      {{}, "empty"},
      {{0x01, 0x02, 0x00}, "shorter than its 5-byte header"},
      {{0x02, 0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00}, "no services"},
      {{0x09, 0x00}, "unknown binary opcode 0x09"},
      {std::vector<std::uint8_t>(kMaxClientMessageBytes + 1, 0x01), "at most 65536"},
  };
  for (const auto& [frame, expected] : cases) {
    auto parsed = parse_client_binary(frame);
    ASSERT_FALSE(parsed) << expected;
    EXPECT_NE(parsed.error().message.find(expected), std::string::npos) << parsed.error().message;
  }
}

}  // namespace
}  // namespace hubrt::hubctl::foxglove
