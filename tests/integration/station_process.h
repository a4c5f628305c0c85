// The whole simulated station as processes, in a test's own DDS domain on loopback: the Tool, RSP
// and Dock ECUs (three hubd on the simulation board, in the layout asked for) and the station
// model (hubsim); with `full`, also the MiR100's mir_com and the operator hub on their simulation
// boards, the Tool ECU with the operator interlock (hubs/station/hub-files) and hubsim with the
// mobile platform (hubs/station/full-station.yaml). Scenarios run against it with `hubctl play`.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/hub_process.h"
#include "hubrt/test_support/test_domain.h"

namespace hubrt::integration {
using test_support::Finished;

enum class StationLayout : std::uint8_t { kNodeType, kHub };

struct StationOptions {
  StationLayout layout = StationLayout::kNodeType;
  bool full = false;                     // the full station (above), for full-use-case.yaml
  std::vector<std::string> hubd_args;    // e.g. {"--rate", "20"}
  std::vector<std::string> hubsim_args;  // e.g. {"--travel-ms", "150"}
  double lift_speed_mm_s = 0;            // > 0: overrides the Tool ECU's lift speed
  // Non-empty: DDS Security from this station folder (hubctl security init/add), each hub as the
  // identity named after it, hubsim as "hubsim", hubctl play as "planner".
  std::string security_dir;
  // Non-empty ("/cell_a"): the station under this ROS namespace — its hubs' (namespace: in their
  // hub files, the other hubs' States they read under it too), hubsim's and play's (--namespace),
  // for stations sharing one domain (docs/plant.md).
  std::string ros_namespace;
};

// Move-only. The destructor stops every process (ChildProcess kills what still runs) and removes
// the hub files it wrote. Not thread-safe.
class StationProcesses {
 public:
  // Writes the hub files (the shipped ones, or the station's for the full station, turned to the
  // hub layout when asked: layout, and the subscriptions to the other hubs' States), starts the
  // hubs and hubsim and waits until each says it runs. Errors carry the output of the process
  // that did not start.
  static Expected<StationProcesses> start(const test_support::TestDomain& domain,
                                          const StationOptions& options);

  ~StationProcesses();
  StationProcesses(StationProcesses&&) noexcept = default;
  StationProcesses& operator=(StationProcesses&&) noexcept = default;

  // Runs `hubctl play <scenario>` (a path) in the station's domain to its end, or until
  // `timeout`. Errors: hubctl could not start, or did not finish in time (kTimeout, with its
  // output so far).
  Expected<Finished> play(const std::string& scenario, Duration timeout);

  // Every process's output, for failure messages.
  [[nodiscard]] std::string logs() const;

 private:
  StationProcesses(const test_support::TestDomain& domain, std::string dir, std::string security_dir,
                   std::string ros_namespace)
      : domain_(&domain),
        dir_(std::move(dir)),
        security_dir_(std::move(security_dir)),
        ros_namespace_(std::move(ros_namespace)) {}

  const test_support::TestDomain* domain_;
  std::string dir_;  // the hub files; removed by the destructor ("" once moved from)
  std::string security_dir_;
  std::string ros_namespace_;
  std::vector<std::pair<std::string, test_support::ChildProcess>> hubs_;  // hubd by hub
  std::optional<test_support::ChildProcess> hubsim_;
};

}  // namespace hubrt::integration
