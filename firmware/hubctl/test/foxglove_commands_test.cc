// The command writers of hubctl foxglove --allow-publish on a private loopback domain: a client's
// CDR bytes arrive at a hub's reader as the command they encode; bytes Cyclone would refuse from
// the network are refused here and nothing is written; only registered command types; one writer
// per topic while a client uses it, a bounded number of topics; with DDS Security, hubctl's
// identity bounds them all: as an observer no client can have a command written.
#include "foxglove_commands.h"

#include <ctime>
#include <filesystem>

#include <gtest/gtest.h>

#include "hubrt/dds/cdr_codec.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/json.h"
#include "hubrt/security/participant_security.h"
#include "hubrt/security/pki.h"
#include "hubrt/test_support/test_domain.h"

#include "role_permissions.h"

namespace hubrt::hubctl::foxglove {
namespace {

// Discovery and delivery take milliseconds; generous for sanitizer builds on a loaded machine.
constexpr auto kPatience = std::chrono::seconds(30);

class CommandWritersTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto bridge = dds::Participant::create(domain_->config(), "foxglove");
    auto hub = dds::Participant::create(domain_->config(), "hub");
    ASSERT_TRUE(bridge && hub);
    bridge_.emplace(std::move(*bridge));
    hub_.emplace(std::move(*hub));
    type_ = msgs::all_types().find("hub_msgs/msg/DockCommand");
    ASSERT_NE(type_, nullptr);
  }

  std::vector<std::uint8_t> encoded(const std::string& action) const {
    dds::UntypedSample sample(*type_->descriptor);
    EXPECT_TRUE(msgs::from_json(
        *type_, nlohmann::ordered_json{{"target_type", "dock"}, {"target_name", "dock"}, {"action", action}},
        sample.data()));
    auto codec = dds::CdrCodec::create(*bridge_, *type_->descriptor);
    EXPECT_TRUE(codec);
    auto bytes = codec->encode(sample.data());
    EXPECT_TRUE(bytes);
    return *bytes;
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> bridge_;
  std::optional<dds::Participant> hub_;
  const msgs::TypeInfo* type_ = nullptr;
};

TEST_F(CommandWritersTest, AClientsBytesReachTheHubAsTheCommand) {
  auto topic = dds::UntypedTopic::create(*hub_, *type_->descriptor, "/dock/command");
  ASSERT_TRUE(topic);
  auto reader = dds::UntypedReader::create(*hub_, *topic);
  ASSERT_TRUE(reader);
  DdsCommandWriters writers(*bridge_, 4);
  auto writer = writers.open("/dock/command", "hub_msgs/DockCommand");  // the short name too
  ASSERT_TRUE(writer) << writer.error().message;
  // Not yet matched: keep writing until the hub's reader has one (volatile, as a planner's).
  dds::UntypedSample got(*type_->descriptor);
  const auto deadline = std::chrono::steady_clock::now() + kPatience;
  bool taken = false;
  while (!taken && std::chrono::steady_clock::now() < deadline) {
    ASSERT_TRUE((*writer)->write(encoded("lock")).is_ok());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const Result<bool> next = reader->take_next(got.data());
    taken = next.is_ok() && next.value();
  }
  ASSERT_TRUE(taken);
  auto value = msgs::to_json(*type_, got.data());
  EXPECT_EQ(value["action"], "lock");
  EXPECT_EQ(value["target_name"], "dock");
}

TEST_F(CommandWritersTest, BytesCycloneWouldRefuseAreNotWritten) {
  DdsCommandWriters writers(*bridge_, 4);
  auto writer = writers.open("/dock/command", "hub_msgs/msg/DockCommand");
  ASSERT_TRUE(writer) << writer.error().message;
  std::vector<std::uint8_t> bytes = encoded("lock");
  bytes[4] = 0xFF;  // the first string's length now runs far past the payload
  EXPECT_EQ((*writer)->write(bytes).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ((*writer)->write(std::vector<std::uint8_t>{0x00, 0x01}).code(), ErrorCode::kInvalidArgument);
}

TEST_F(CommandWritersTest, OnlyCommandTypesAndABoundedNumberOfTopics) {
  DdsCommandWriters writers(*bridge_, 2);
  auto state = writers.open("/dock/command", "hub_msgs/msg/DockState");
  ASSERT_FALSE(state);
  EXPECT_NE(state.error().message.find("no command type"), std::string::npos);
  EXPECT_FALSE(writers.open("/dock/command", "no_such/msg/Thing"));
  auto a = writers.open("/dock/command", "hub_msgs/msg/DockCommand");
  auto again = writers.open("/dock/command", "hub_msgs/msg/DockCommand");
  ASSERT_TRUE(a && again);
  EXPECT_EQ(a->get(), again->get());  // one writer per topic
  auto other = writers.open("/dock/command", "hub_msgs/msg/LiftCommand");
  ASSERT_FALSE(other);
  EXPECT_NE(other.error().message.find("written as"), std::string::npos);
  auto b = writers.open("/lift/command", "hub_msgs/msg/LiftCommand");
  ASSERT_TRUE(b) << b.error().message;
  auto c = writers.open("/tool/command", "hub_msgs/msg/SmartToolCommand");
  ASSERT_FALSE(c);
  EXPECT_EQ(c.error().code, ErrorCode::kOutOfRange);
  b->reset();  // the last client of /lift/command let go: its place is free
  EXPECT_TRUE(writers.open("/tool/command", "hub_msgs/msg/SmartToolCommand"));
}

// The station's PKI as `hubctl security init/add` makes it, an observer and a planner in it.
TEST(CommandWritersSecurity, TheIdentityBoundsWhatAnyClientCanPublish) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  namespace fs = std::filesystem;
  std::string dir = (fs::temp_directory_path() / "hubrt-foxglove-pki-XXXXXX").string();
  ASSERT_NE(::mkdtemp(dir.data()), nullptr);
  const std::string station = dir + "/station";
  const std::int64_t now = std::time(nullptr);
  const security::Validity validity{now - 3600, now + 86400};
  ASSERT_TRUE(security::init_station(station, validity));
  for (const char* role : {"observer", "planner"}) {
    auto topics = role_permissions(role, {}, false);
    ASSERT_TRUE(topics) << topics.error().message;
    auto added = security::add_identity(station, role, validity, topics->publish, topics->subscribe);
    ASSERT_TRUE(added) << added.error().message;
  }
  // One participant at a time: Cyclone keeps one configuration per domain and process.
  const auto open_as = [&](const std::string& identity) -> Expected<void> {
    auto secured = security::security_xml_for({station, identity}, now);
    if (!secured) return std::move(secured).error();
    dds::DomainConfig config = domain->config();
    config.cyclone_xml = security::with_security(config.cyclone_xml, *secured);
    auto participant = dds::Participant::create(config, "foxglove");
    if (!participant) return std::move(participant).error();
    DdsCommandWriters writers(*participant, 4);
    auto writer = writers.open("/dock/command", "hub_msgs/msg/DockCommand");
    if (!writer) return std::move(writer).error();
    return {};
  };
  auto observer = open_as("observer");
  ASSERT_FALSE(observer);
  // "create writer on 'rt/dock/command' in domain N: DDS_RETCODE_NOT_ALLOWED_BY_SECURITY (...)"
  EXPECT_NE(observer.error().message.find("NOT_ALLOWED_BY_SECURITY"), std::string::npos)
      << observer.error().message;
  auto planner = open_as("planner");
  EXPECT_TRUE(planner) << planner.error().message;
  std::error_code ignored;
  fs::remove_all(dir, ignored);
}

}  // namespace
}  // namespace hubrt::hubctl::foxglove
