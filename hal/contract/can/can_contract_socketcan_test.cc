// The CanBus contract on the SocketCAN backend, for the kernel tier: needs a kernel with vcan and
// can_raw, an interface (HUBRT_TEST_CAN_INTERFACE, default "vcan0") that exists, and the right to
// take it down and up (root in the test VM). Labelled "kernel": not in the default suite.
// vcan has no controller to drive into bus-off; the harness sends the error frames a controller
// would report (bus-off, then restarted) from a helper socket, so the backend's error-frame path
// runs through the real kernel.
#include <unistd.h>

#include <cstdlib>
#include <cstring>

#include <linux/can.h>
#include <linux/can/error.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>

#include "hubrt/hal/socketcan/open_socketcan.h"

#include "can_contract.h"

namespace hubrt::hal::contract {
namespace {

std::string test_interface() {
  const char* name =
      std::getenv("HUBRT_TEST_CAN_INTERFACE");  // NOLINT(concurrency-mt-unsafe): read before threads start
  return name != nullptr && *name != '\0' ? name : "vcan0";
}

// Administrative up/down, as `ip link set <if> up|down` does it.
bool set_interface_up(const std::string& interface, bool up) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return false;
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, interface.c_str(), IFNAMSIZ - 1);
  bool ok = ::ioctl(fd, SIOCGIFFLAGS, &ifr) == 0;
  if (ok) {
    ifr.ifr_flags = static_cast<short>(up ? (ifr.ifr_flags | IFF_UP) : (ifr.ifr_flags & ~IFF_UP));
    ok = ::ioctl(fd, SIOCSIFFLAGS, &ifr) == 0;
  }
  ::close(fd);
  return ok;
}

// Sends one error frame with these classes on `interface`, as a controller's driver reports one.
bool report_error(const std::string& interface, canid_t classes) {
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) return false;
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(::if_nametoindex(interface.c_str()));
  can_frame frame{};
  frame.can_id = CAN_ERR_FLAG | classes;
  frame.len = CAN_ERR_DLC;
  const bool ok = addr.can_ifindex != 0 && ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0 &&
                  ::write(fd, &frame, sizeof frame) == static_cast<ssize_t>(sizeof frame);
  ::close(fd);
  return ok;
}

class SocketCanHarness final : public CanContractHarness {
 public:
  Expected<std::unique_ptr<CanBus>> open_node(const std::vector<CanFilter>& filters) override {
    CanConfig config;
    config.bus = "contract";
    config.interface = interface_;
    config.filters = filters;
    return socketcan::open_socketcan(config);
  }
  bool inject_bus_state(CanBusState state) override {
    switch (state) {
      case CanBusState::kDown:
        return set_interface_up(interface_, false);
      case CanBusState::kBusOff:
        return report_error(interface_, CAN_ERR_BUSOFF);
      case CanBusState::kErrorActive:
        return set_interface_up(interface_, true) && report_error(interface_, CAN_ERR_RESTARTED);
      default:
        return false;
    }
  }

 private:
  std::string interface_ = test_interface();
};

INSTANTIATE_TEST_SUITE_P(SocketCan, CanContract,
                         ::testing::Values(CanContractBackend{
                             "SocketCan", [] { return std::make_unique<SocketCanHarness>(); }}),
                         CanContractName{});

}  // namespace
}  // namespace hubrt::hal::contract
