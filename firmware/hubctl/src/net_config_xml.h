// The Cyclone DDS configuration of one host of a station on several hosts (station_network.h):
// what `hubctl net-config <station.yaml> --host <name>` prints.
#pragma once

#include <string>
#include <string_view>

#include "hubrt/base/status.h"

#include "station_network.h"

namespace hubrt::hubctl {

// The XML for `host`: DDS on that host's interface only (by name when the station file names
// one, else by its address), multicast off (a VPN or a switched network may not carry it, and
// nothing outside the station should answer), discovery by unicast to every host of the station
// — this one too, for its own other processes — with automatic participant indices up to
// station.max_participant_index() (MaxAutoParticipantIndex one more), and hubrt's resource bounds
// (dds::resource_bounds_elements_xml: receive buffer, largest sample). A comment says which host runs what
// and which UDP ports the firewall must let through between the hosts. Applies to any domain id (the
// station's is in ROS_DOMAIN_ID). Errors: kNotFound naming the host and the station's hosts when `host` is
// not one of them.
Expected<std::string> cyclone_config_for_host(const StationNetwork& station, std::string_view host);

}  // namespace hubrt::hubctl
