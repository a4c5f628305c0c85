// Which of the domain's topics the tap takes: the station's traffic by default — every hub State,
// every command, /diagnostics and the simulation's /sim topics — or the topics named, or those
// matching a regular expression, or every topic of a type this hubctl knows.
#pragma once

#include <functional>
#include <regex>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/msgs/type_info.h"

namespace hubrt::hubctl {

// Says whether the tap takes a discovered topic (ROS name, its registered type). Called on the
// tap's thread; must not block.
using TapFilter = std::function<bool(std::string_view ros_name, const msgs::TypeInfo& type)>;

// True for the station's traffic: a State (hubctl conformance's test: a type with `echo` and
// `fresh_msg`), a command (a hub_msgs type named ...Command), /diagnostics, /sim/... topics.
bool is_station_traffic(std::string_view ros_name, const msgs::TypeInfo& type) noexcept;
// True for a State type (what watch and serve show).
bool is_state_topic(std::string_view ros_name, const msgs::TypeInfo& type) noexcept;
// True for a command type (what `hubctl play` replays by default).
bool is_command_type(const msgs::TypeInfo& type) noexcept;

struct TapChoice {
  std::vector<std::string> topics;  // exact ROS names ("rt/..." accepted)
  std::string regex;                // ECMAScript, matched against the whole ROS name
  bool all = false;                 // every topic of a known type
};

// The filter for `choice`: the named topics and the regex's matches together; with neither,
// every topic when `all`, else the station's traffic. Errors: kInvalidArgument for a regex that
// does not compile or a topic that is not a ROS name.
Expected<TapFilter> make_tap_filter(const TapChoice& choice);

}  // namespace hubrt::hubctl
