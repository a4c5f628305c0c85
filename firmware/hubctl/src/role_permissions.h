// What each kind of station participant may publish and subscribe, as DDS topic expressions for
// its permissions document (hubctl security add --role ...).
#pragma once

#include <string>
#include <vector>

#include "hubrt/base/status.h"

namespace hubrt::hubctl {

struct TopicPermissions {
  std::vector<std::string> publish;
  std::vector<std::string> subscribe;
};

// Roles:
//   planner   publishes every command topic (rt/*/command), reads everything
//   observer  reads everything, publishes nothing
//   hub       for each hub file in `hubs` (path or hub type, found as hubd finds it): publishes
//             its own State topics (one per node, or the hub's) and /diagnostics; reads the
//             command topics its nodes answer and the State topics its `subscriptions:` name
//   simulator hubsim: reads and writes the simulation topics (rt/sim/*)
// With `simulation`, planner and hub also get the simulation topics they use on the simulated
// station (the planner drives /sim/station/command, /sim/input and /sim/fault; a hub reads
// /sim/input and /sim/fault and writes /sim/<hub>/signals).
// Errors: kInvalidArgument for an unknown role, a hub role without hubs or hubs with another
// role; a hub file's load error as the loader gives it.
Expected<TopicPermissions> role_permissions(const std::string& role, const std::vector<std::string>& hubs,
                                            bool simulation);

}  // namespace hubrt::hubctl
