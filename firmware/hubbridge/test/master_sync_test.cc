// MasterSync against a fake ROS 1 graph: what hubbridge tells a restarted master, in which order,
// and that it never tells its own subscriptions a list of publishers lacking one it is connected to
// (roscpp would drop that link: Subscription::pubUpdate).
#include "master_sync.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace hubrt::hubbridge {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

constexpr const char* kOwn = "/dock_ecu";
constexpr const char* kOwnUri = "http://bridge:1000/";
constexpr const char* kEcu = "/dock_ecu_ros1_42";
constexpr const char* kEcuUri = "http://ecu:2000/";

// A master (pid, registrations, nodes) and hubbridge's own node (links), recording every call.
class FakeGraph final : public Ros1Graph {
 public:
  int pid = 0;
  std::map<std::string, std::string> nodes;  // what lookupNode answers
  SystemState state;
  std::vector<Link> links;
  std::vector<std::string> calls;

  int master_pid() override { return pid; }
  std::optional<SystemState> system_state() override { return state; }
  std::optional<std::string> lookup_node(const std::string& name) override {
    const auto it = nodes.find(name);
    return it == nodes.end() ? std::nullopt : std::optional(it->second);
  }
  bool register_publisher(const std::string& caller_id, const std::string& caller_api,
                          const std::string& topic, const std::string& type) override {
    calls.push_back(fmt::format("registerPublisher {} {} {} {}", caller_id, caller_api, topic, type));
    add(state.publishers[topic], caller_id);
    nodes.emplace(caller_id, caller_api);
    return true;
  }
  std::optional<std::vector<std::string>> register_subscriber(const std::string& caller_id,
                                                              const std::string& caller_api,
                                                              const std::string& topic,
                                                              const std::string& type) override {
    calls.push_back(fmt::format("registerSubscriber {} {} {} {}", caller_id, caller_api, topic, type));
    add(state.subscribers[topic], caller_id);
    nodes.emplace(caller_id, caller_api);
    std::vector<std::string> uris;
    for (const auto& name : state.publishers[topic]) uris.push_back(nodes[name]);
    return uris;
  }
  [[nodiscard]] std::string own_name() const override { return kOwn; }
  [[nodiscard]] std::string own_uri() const override { return kOwnUri; }
  std::vector<Link> own_links() override { return links; }
  void own_publisher_update(const std::string& topic, const std::vector<std::string>& publishers) override {
    calls.push_back(fmt::format("publisherUpdate {} [{}]", topic, fmt::join(publishers, " ")));
  }

  // A fresh master: it knows nobody.
  void restart_master() {
    ++pid;
    nodes.clear();
    state = {};
  }

 private:
  static void add(std::vector<std::string>& list, const std::string& name) {
    if (std::find(list.begin(), list.end(), name) == list.end()) list.push_back(name);
  }
};

const std::vector<SyncedEndpoint> kEndpoints = {{"/state", "hub_msgs/DockState", true},
                                                {"/command", "hub_msgs/DockCommand", false}};

// The station before the restart: hubbridge and the ECU registered, linked both ways.
FakeGraph running_station() {
  FakeGraph graph;
  graph.pid = 7;
  graph.nodes = {{kOwn, kOwnUri}, {kEcu, kEcuUri}};
  graph.state.publishers = {{"/state", {kEcu}}, {"/command", {kOwn}}};
  graph.state.subscribers = {{"/state", {kOwn}}, {"/command", {kEcu}}};
  graph.links = {{"/state", true, kEcuUri}, {"/command", false, kEcu}};
  return graph;
}

std::vector<std::vector<std::string>> ecu_heard() {
  return {{kEcu}, {}};
}

MasterSync registered(FakeGraph& graph, bool register_lost = true) {
  MasterSync sync(graph, kEndpoints, register_lost);
  EXPECT_EQ(sync.turn(ecu_heard()), MasterSync::Action::kRegisterFirst);
  sync.registered_first();
  EXPECT_EQ(sync.turn(ecu_heard()), MasterSync::Action::kNone);  // learns the ECU's URI
  return sync;
}

TEST(MasterSync, WaitsForAMasterThenAsksForTheFirstRegistration) {
  FakeGraph graph;
  MasterSync sync(graph, kEndpoints, true);
  EXPECT_EQ(sync.turn({}), MasterSync::Action::kNone);
  graph.pid = 7;
  EXPECT_EQ(sync.turn({}), MasterSync::Action::kRegisterFirst);
  sync.registered_first();
  EXPECT_EQ(sync.turn({}), MasterSync::Action::kNone);
  EXPECT_EQ(sync.registrations(), 1U);
  EXPECT_THAT(graph.calls, IsEmpty()) << "roscpp registered the endpoints, not MasterSync";
}

TEST(MasterSync, MasterAwayChangesNothing) {
  FakeGraph graph = running_station();
  MasterSync sync = registered(graph);
  graph.calls.clear();
  graph.pid = 0;
  EXPECT_EQ(sync.turn(ecu_heard()), MasterSync::Action::kNone);
  EXPECT_THAT(graph.calls, IsEmpty());
  EXPECT_EQ(sync.registrations(), 1U);
}

// The restart of issue 34: the ECU is registered on its behalf before hubbridge's own
// subscription, so the new master's answer lists it; no publisherUpdate is sent (nothing new),
// so the link is never dropped; the ECU's subscription is registered too.
TEST(MasterSync, RestartRegistersTheNodesItIsLinkedToOnTheirBehalf) {
  FakeGraph graph = running_station();
  MasterSync sync = registered(graph);
  graph.calls.clear();
  graph.restart_master();
  EXPECT_EQ(sync.turn(ecu_heard()), MasterSync::Action::kNone);
  EXPECT_THAT(
      graph.calls,
      ElementsAre("registerPublisher /dock_ecu_ros1_42 http://ecu:2000/ /state hub_msgs/DockState",
                  "registerPublisher /dock_ecu http://bridge:1000/ /command hub_msgs/DockCommand",
                  "registerSubscriber /dock_ecu_ros1_42 http://ecu:2000/ /command hub_msgs/DockCommand",
                  "registerSubscriber /dock_ecu http://bridge:1000/ /state hub_msgs/DockState"));
  EXPECT_EQ(sync.registrations(), 2U);
  EXPECT_THAT(sync.status()[0].registered_for, ElementsAre(kEcu));
  EXPECT_THAT(sync.status()[0].unregistered, IsEmpty());
  EXPECT_THAT(sync.status()[1].registered_for, ElementsAre(kEcu));
  graph.calls.clear();
  EXPECT_EQ(sync.turn(ecu_heard()), MasterSync::Action::kNone);
  EXPECT_THAT(graph.calls, IsEmpty()) << "once registered, nothing more to do";
}

// A publisher the new master knows and hubbridge is not linked to joins; the linked one stays in
// the list hubbridge gives itself.
TEST(MasterSync, PublishersOnlyTheNewMasterKnowsJoinTheLinkedOnes) {
  FakeGraph graph = running_station();
  MasterSync sync = registered(graph, false);
  graph.calls.clear();
  graph.restart_master();
  graph.nodes["/other"] = "http://other:3000/";
  graph.state.publishers["/state"] = {"/other"};
  (void)sync.turn(ecu_heard());
  EXPECT_THAT(graph.calls,
              ElementsAre("registerPublisher /dock_ecu http://bridge:1000/ /command hub_msgs/DockCommand",
                          "registerSubscriber /dock_ecu http://bridge:1000/ /state hub_msgs/DockState",
                          "publisherUpdate /state [http://ecu:2000/ http://other:3000/]"));
}

// register_lost_publishers: false: only hubbridge's own endpoints, and the ECU is reported.
TEST(MasterSync, WithoutRegisteringForOthersTheLostPublisherIsReported) {
  FakeGraph graph = running_station();
  MasterSync sync = registered(graph, false);
  graph.calls.clear();
  graph.restart_master();
  (void)sync.turn(ecu_heard());
  EXPECT_THAT(graph.calls,
              ElementsAre("registerPublisher /dock_ecu http://bridge:1000/ /command hub_msgs/DockCommand",
                          "registerSubscriber /dock_ecu http://bridge:1000/ /state hub_msgs/DockState"));
  EXPECT_THAT(sync.status()[0].unregistered, ElementsAre(kEcu));
  // Once it is silent (not heard any more) it is no longer reported.
  (void)sync.turn({{}, {}});
  EXPECT_THAT(sync.status()[0].unregistered, IsEmpty());
}

// A node the new master already knows at another URI restarted meanwhile: registering the old URI
// under its name would make the master tell the new one to shut down.
TEST(MasterSync, NeverRegistersANodeTheMasterKnowsAtAnotherUri) {
  FakeGraph graph = running_station();
  MasterSync sync = registered(graph);
  graph.calls.clear();
  graph.restart_master();
  graph.nodes[kEcu] = "http://ecu:2999/";
  (void)sync.turn(ecu_heard());
  for (const auto& call : graph.calls) EXPECT_EQ(call.find(kEcuUri), std::string::npos) << call;
  EXPECT_THAT(sync.status()[0].unregistered, ElementsAre(kEcu));
}

// Only a publisher a master listed for the topic is vouched for: one heard but never listed (its
// name is all hubbridge has) is reported, not registered.
TEST(MasterSync, APublisherNoMasterListedIsReportedNotRegistered) {
  FakeGraph graph = running_station();
  MasterSync sync = registered(graph);
  graph.calls.clear();
  (void)sync.turn({{kEcu, "/stranger"}, {}});
  EXPECT_THAT(graph.calls, IsEmpty());
  EXPECT_THAT(sync.status()[0].unregistered, ElementsAre("/stranger"));
}

}  // namespace
}  // namespace hubrt::hubbridge
