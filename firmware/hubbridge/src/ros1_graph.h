// What hubbridge asks of the ROS 1 graph over XML-RPC: the master (ROS Master API: getPid,
// getSystemState, lookupNode, registerPublisher, registerSubscriber) and its own node (ROS Slave
// API: getBusInfo, publisherUpdate). An interface, so that MasterSync (master_sync.h) is tested
// without a master; XmlRpcRos1Graph is the real one, on roscpp's XML-RPC client.
//
// APIs: wiki.ros.org/ROS/Master_API and wiki.ros.org/ROS/Slave_API; what roscpp 1.15 answers is
// in ros_comm clients/roscpp/src/libros/topic_manager.cpp (getBusInfo: one entry per connection,
// [id, peer, 'i' | 'o', transport, topic, ...], the peer a publisher's XML-RPC URI for 'i' and a
// subscriber's caller id for 'o'; publisherUpdate: Subscription::pubUpdate, which connects to the
// URIs it does not know and drops every connection to a publisher the list lacks).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace hubrt::hubbridge {

class Ros1Graph {
 public:
  virtual ~Ros1Graph() = default;

  // The master's process id; 0 when it does not answer.
  virtual int master_pid() = 0;

  // getSystemState: topic -> the caller ids of its publishers and of its subscribers.
  struct SystemState {
    std::map<std::string, std::vector<std::string>> publishers;
    std::map<std::string, std::vector<std::string>> subscribers;
  };
  // nullopt when the master does not answer or answers something else than the API's shape.
  virtual std::optional<SystemState> system_state() = 0;

  // lookupNode: the node's XML-RPC URI as the master knows it; nullopt when it does not.
  virtual std::optional<std::string> lookup_node(const std::string& name) = 0;

  // registerPublisher / registerSubscriber as `caller_id` at `caller_api`: hubbridge's own
  // endpoints, or a node's on its behalf. False when the master refused or did not answer.
  // register_subscriber's publishers: the XML-RPC URIs the master lists for the topic.
  virtual bool register_publisher(const std::string& caller_id, const std::string& caller_api,
                                  const std::string& topic, const std::string& type) = 0;
  virtual std::optional<std::vector<std::string>> register_subscriber(const std::string& caller_id,
                                                                      const std::string& caller_api,
                                                                      const std::string& topic,
                                                                      const std::string& type) = 0;

  // hubbridge's own node: its name and XML-RPC URI.
  [[nodiscard]] virtual std::string own_name() const = 0;
  [[nodiscard]] virtual std::string own_uri() const = 0;

  // The node's own connections (getBusInfo). inbound: `peer` is the publisher's XML-RPC URI;
  // outbound: the subscriber's caller id.
  struct Link {
    std::string topic;
    bool inbound = false;
    std::string peer;
  };
  virtual std::vector<Link> own_links() = 0;

  // publisherUpdate on the node itself: roscpp connects to every URI of `publishers` it has no
  // connection to, and drops those it has that the list lacks.
  virtual void own_publisher_update(const std::string& topic, const std::vector<std::string>& publishers) = 0;
};

// Ros1Graph over roscpp: ros::master::execute for the master (no waiting for it), an
// XmlRpc::XmlRpcClient for the node's own slave API (answered by roscpp's XML-RPC thread).
// Requires ros::init; call from one thread at a time.
class XmlRpcRos1Graph final : public Ros1Graph {
 public:
  int master_pid() override;
  std::optional<SystemState> system_state() override;
  std::optional<std::string> lookup_node(const std::string& name) override;
  bool register_publisher(const std::string& caller_id, const std::string& caller_api,
                          const std::string& topic, const std::string& type) override;
  std::optional<std::vector<std::string>> register_subscriber(const std::string& caller_id,
                                                              const std::string& caller_api,
                                                              const std::string& topic,
                                                              const std::string& type) override;
  [[nodiscard]] std::string own_name() const override;
  [[nodiscard]] std::string own_uri() const override;
  std::vector<Link> own_links() override;
  void own_publisher_update(const std::string& topic, const std::vector<std::string>& publishers) override;
};

}  // namespace hubrt::hubbridge
