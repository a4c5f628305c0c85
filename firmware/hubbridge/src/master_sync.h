// Keeping the ROS 1 graph whole across rosmaster restarts (docs/ros1-bridge.md, "rosmaster
// restarts").
//
// A restarted master knows nobody, and roscpp registers nothing again by itself. The links
// between nodes are TCP connections that do not need the master, so they outlive it — until a
// subscriber is told (by registerSubscriber's answer or a publisherUpdate from the master) a list
// of publishers that lacks one it is connected to: roscpp then drops that link
// (Subscription::pubUpdate). hubbridge therefore:
//   - registers its own endpoints with a restarted master by XML-RPC (registerPublisher,
//     registerSubscriber: the calls roscpp makes) instead of shutting them down and subscribing
//     again, so that no link of its own goes;
//   - registers the publishers it hears from (a message within the silence window, so alive and
//     publishing) and the subscribers connected to it with the new master on their behalf, with
//     the caller id and XML-RPC URI an earlier master listed for that topic — as rosnode cleanup
//     unregisters dead nodes on their behalf, and for the same reason: the master's lists are what
//     every node is told. Never a node the current master knows at another URI (the master would
//     tell that one to shut down as a duplicate name);
//   - tells its own subscriptions of the publishers the new master lists, keeping those it is
//     connected to (a publisherUpdate on itself with both);
//   - reports a publisher it hears but the master does not list ("unregistered") on /diagnostics.
// With register_lost_publishers off (the bridge file's key) only hubbridge's own endpoints are
// registered; the links are kept all the same and unregistered publishers are reported.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "ros1_graph.h"

namespace hubrt::hubbridge {

// One bridge's ROS 1 endpoint.
struct SyncedEndpoint {
  std::string topic;        // the ROS 1 topic
  std::string type;         // its ROS 1 type, "hub_msgs/DockState"
  bool subscribes = false;  // ros1_to_dds: hubbridge subscribes, nodes publish
};

// What one endpoint looks like from the master's side, for /diagnostics.
struct EndpointSync {
  std::vector<std::string> unregistered;    // heard publishers the master does not list
  std::vector<std::string> registered_for;  // nodes registered on their behalf with this master
};

class MasterSync {
 public:
  static constexpr std::size_t kMaxKnownPerEndpoint = 32;  // names remembered per topic
  static constexpr std::size_t kMaxLookupsPerTurn = 16;    // lookupNode calls per turn

  MasterSync(Ros1Graph& graph, std::vector<SyncedEndpoint> endpoints, bool register_lost_publishers);

  enum class Action : std::uint8_t {
    kNone,
    kRegisterFirst,  // a master answers and hubbridge never registered: subscribe and advertise
                     // through roscpp, then call registered_first()
  };

  // One turn, about once a second, from the thread that owns the ROS 1 endpoints. `heard[i]`:
  // the caller ids endpoints()[i] received a message from within the silence window (empty for
  // publishing endpoints). Asks the master for its pid; after a restart registers everything
  // again (see the file comment); then reads the master's lists and registers or reports the
  // publishers it lacks.
  Action turn(const std::vector<std::vector<std::string>>& heard);

  // roscpp registered hubbridge's endpoints with the master whose pid turn() saw last.
  void registered_first();

  [[nodiscard]] const std::vector<SyncedEndpoint>& endpoints() const { return endpoints_; }
  [[nodiscard]] const std::vector<EndpointSync>& status() const { return status_; }
  // Registrations of hubbridge's endpoints with a master (the first, then one per restart).
  [[nodiscard]] std::uint64_t registrations() const { return registrations_; }

 private:
  void register_again(const std::vector<std::vector<std::string>>& heard);
  void learn(const Ros1Graph::SystemState& state);
  void register_lost(std::size_t index, const std::vector<std::string>& heard,
                     const std::vector<std::string>& listed);
  bool register_for(std::size_t index, const std::string& name, bool as_publisher);

  Ros1Graph& graph_;
  std::vector<SyncedEndpoint> endpoints_;
  bool register_lost_publishers_;
  int master_pid_ = 0;       // the pid seen last; 0: none answered
  int registered_with_ = 0;  // the pid hubbridge's endpoints are registered with; 0: none
  std::uint64_t registrations_ = 0;
  std::vector<std::map<std::string, std::string>> known_;  // per endpoint: caller id -> XML-RPC URI
  std::vector<std::set<std::string>> attempted_;           // per endpoint: tried with this master
  std::vector<EndpointSync> status_;
};

}  // namespace hubrt::hubbridge
