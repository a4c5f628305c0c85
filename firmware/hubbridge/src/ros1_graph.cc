#include "ros1_graph.h"

#include <ros/master.h>
#include <ros/network.h>
#include <ros/this_node.h>
#include <ros/xmlrpc_manager.h>
#include <xmlrpcpp/XmlRpcClient.h>
#include <xmlrpcpp/XmlRpcException.h>

namespace hubrt::hubbridge {
namespace {

using XmlRpc::XmlRpcValue;

// The master's answer to `method` (its payload), or nullopt. No waiting for a master that is
// away: the caller asks again on its next turn.
std::optional<XmlRpcValue> ask_master(const char* method, const XmlRpcValue& args) {
  XmlRpcValue result;
  XmlRpcValue payload;
  if (!ros::master::execute(method, args, result, payload, false)) return std::nullopt;
  return payload;
}

std::optional<std::string> string_of(XmlRpcValue& value) {
  if (value.getType() != XmlRpcValue::TypeString) return std::nullopt;
  return static_cast<std::string>(value);
}

// [[topic, [caller ids]], ...] of getSystemState.
std::map<std::string, std::vector<std::string>> topic_lists(XmlRpcValue& list) {
  std::map<std::string, std::vector<std::string>> out;
  if (list.getType() != XmlRpcValue::TypeArray) return out;
  for (int i = 0; i < list.size(); ++i) {
    XmlRpcValue& entry = list[i];
    if (entry.getType() != XmlRpcValue::TypeArray || entry.size() != 2) continue;
    const auto topic = string_of(entry[0]);
    if (!topic || entry[1].getType() != XmlRpcValue::TypeArray) continue;
    auto& names = out[*topic];
    for (int j = 0; j < entry[1].size(); ++j) {
      if (auto name = string_of(entry[1][j])) names.push_back(std::move(*name));
    }
  }
  return out;
}

// One call of the node's own slave API; its value (the third element of [code, text, value])
// when the code is 1, else nullopt.
std::optional<XmlRpcValue> ask_self(const char* method, const XmlRpcValue& args) {
  std::string host;
  std::uint32_t port = 0;
  if (!ros::network::splitURI(ros::XMLRPCManager::instance()->getServerURI(), host, port))
    return std::nullopt;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpcValue result;
  if (!client.execute(method, args, result) || client.isFault()) return std::nullopt;
  if (result.getType() != XmlRpcValue::TypeArray || result.size() != 3 ||
      result[0].getType() != XmlRpcValue::TypeInt || static_cast<int>(result[0]) != 1) {
    return std::nullopt;
  }
  return result[2];
}

}  // namespace

int XmlRpcRos1Graph::master_pid() {
  XmlRpcValue args;
  args[0] = ros::this_node::getName();
  auto payload = ask_master("getPid", args);
  return payload && payload->getType() == XmlRpcValue::TypeInt ? static_cast<int>(*payload) : 0;
}

std::optional<Ros1Graph::SystemState> XmlRpcRos1Graph::system_state() {
  XmlRpcValue args;
  args[0] = ros::this_node::getName();
  auto payload = ask_master("getSystemState", args);
  if (!payload || payload->getType() != XmlRpcValue::TypeArray || payload->size() < 2) return std::nullopt;
  try {
    return SystemState{topic_lists((*payload)[0]), topic_lists((*payload)[1])};
  } catch (const XmlRpc::XmlRpcException&) {
    return std::nullopt;
  }
}

std::optional<std::string> XmlRpcRos1Graph::lookup_node(const std::string& name) {
  XmlRpcValue args;
  args[0] = ros::this_node::getName();
  args[1] = name;
  auto payload = ask_master("lookupNode", args);
  return payload ? string_of(*payload) : std::nullopt;
}

bool XmlRpcRos1Graph::register_publisher(const std::string& caller_id, const std::string& caller_api,
                                         const std::string& topic, const std::string& type) {
  XmlRpcValue args;
  args[0] = caller_id;
  args[1] = topic;
  args[2] = type;
  args[3] = caller_api;
  return ask_master("registerPublisher", args).has_value();
}

std::optional<std::vector<std::string>> XmlRpcRos1Graph::register_subscriber(const std::string& caller_id,
                                                                             const std::string& caller_api,
                                                                             const std::string& topic,
                                                                             const std::string& type) {
  XmlRpcValue args;
  args[0] = caller_id;
  args[1] = topic;
  args[2] = type;
  args[3] = caller_api;
  auto payload = ask_master("registerSubscriber", args);
  if (!payload || payload->getType() != XmlRpcValue::TypeArray) return std::nullopt;
  std::vector<std::string> publishers;
  for (int i = 0; i < payload->size(); ++i) {
    if (auto uri = string_of((*payload)[i])) publishers.push_back(std::move(*uri));
  }
  return publishers;
}

std::string XmlRpcRos1Graph::own_name() const {
  return ros::this_node::getName();
}

std::string XmlRpcRos1Graph::own_uri() const {
  return ros::XMLRPCManager::instance()->getServerURI();
}

std::vector<Ros1Graph::Link> XmlRpcRos1Graph::own_links() {
  XmlRpcValue args;
  args[0] = ros::this_node::getName();
  std::vector<Link> links;
  auto info = ask_self("getBusInfo", args);
  if (!info || info->getType() != XmlRpcValue::TypeArray) return links;
  for (int i = 0; i < info->size(); ++i) {
    XmlRpcValue& entry = (*info)[i];
    if (entry.getType() != XmlRpcValue::TypeArray || entry.size() < 5) continue;
    auto peer = string_of(entry[1]);
    auto direction = string_of(entry[2]);
    auto topic = string_of(entry[4]);
    if (!peer || !direction || !topic) continue;
    links.push_back(Link{std::move(*topic), *direction == "i", std::move(*peer)});
  }
  return links;
}

void XmlRpcRos1Graph::own_publisher_update(const std::string& topic,
                                           const std::vector<std::string>& publishers) {
  XmlRpcValue args;
  args[0] = std::string("/master");  // the caller a publisherUpdate comes from
  args[1] = topic;
  args[2].setSize(static_cast<int>(publishers.size()));
  for (std::size_t i = 0; i < publishers.size(); ++i) args[2][static_cast<int>(i)] = publishers[i];
  (void)ask_self("publisherUpdate", args);
}

}  // namespace hubrt::hubbridge
