#include "hubrt/hal/socketcan/open_socketcan.h"

#include <libsocketcan.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <spdlog/spdlog.h>
#include <sys/ioctl.h>
#include <sys/socket.h>

#include "socketcan_bus.h"
#include "socketcan_codec.h"

namespace hubrt::hal::socketcan {
namespace {

Error error_from_errno(int err, const std::string& where, const std::string& doing) {
  const std::string cause = std::generic_category().message(err);
  switch (err) {
    case EACCES:
    case EPERM:
      return make_error(ErrorCode::kPermissionDenied, where + ": " + doing + ": " + cause);
    case ENODEV:
    case ENXIO:
      return make_error(ErrorCode::kNotFound, where + ": " + doing + ": " + cause);
    default:
      return make_error(ErrorCode::kIo, where + ": " + doing + ": " + cause);
  }
}

bool interface_is_up(int fd, const std::string& interface) noexcept {
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, interface.c_str(), IFNAMSIZ - 1);
  return ::ioctl(fd, SIOCGIFFLAGS, &ifr) == 0 && (ifr.ifr_flags & IFF_UP) != 0;
}

// Real controllers (SPI, USB, on-chip) have a device behind the interface; vcan and vxcan do not,
// and have no bit timing, state or error counters to ask libsocketcan for (it complains on stderr
// when asked); for them the error frames are the only source of state.
bool has_controller(const std::string& interface) {
  std::error_code ignored;
  return std::filesystem::exists("/sys/class/net/" + interface + "/device", ignored);
}

void warn_on_bitrate_mismatch(const CanConfig& config, const std::string& where) {
  can_bittiming timing{};
  if (can_get_bittiming(config.interface.c_str(), &timing) != 0 || timing.bitrate == 0) return;
  if (timing.bitrate != config.bitrate) {
    spdlog::warn(
        "{}: interface runs at {} bit/s, configuration expects {} bit/s (set it with systemd-networkd)",
        where, timing.bitrate, config.bitrate);
  }
}

}  // namespace

Expected<std::unique_ptr<CanBus>> open_socketcan(const CanConfig& config) {
  const std::string where = config.bus + " (SocketCAN '" + config.interface + "')";
  if (config.interface.empty() || config.interface.size() >= IFNAMSIZ) {
    return make_error(ErrorCode::kInvalidArgument,
                      where + ": interface name must be 1.." + std::to_string(IFNAMSIZ - 1) + " characters");
  }
  std::vector<can_filter> filters;
  if (!to_kernel_filters(config.filters, filters).is_ok()) {
    return make_error(ErrorCode::kInvalidArgument,
                      where + ": invalid CAN filter (id or mask wider than its frame format, or more than " +
                          std::to_string(CAN_RAW_FILTER_MAX) + ")");
  }

  UniqueFd fd(::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW));
  if (fd.get() < 0) {
    const int err = errno;
    if (err == EAFNOSUPPORT || err == EPROTONOSUPPORT) {
      return make_error(ErrorCode::kUnavailable,
                        where + ": this kernel has no SocketCAN (socket(PF_CAN, SOCK_RAW, CAN_RAW): " +
                            std::generic_category().message(err) +
                            "); load the can and can_raw modules (modprobe can_raw)");
    }
    return error_from_errno(err, where, "cannot create a CAN socket");
  }

  const unsigned ifindex = ::if_nametoindex(config.interface.c_str());
  if (ifindex == 0) {
    return make_error(ErrorCode::kNotFound,
                      where + ": no network interface named '" + config.interface + "'");
  }

  const auto filter_bytes = static_cast<socklen_t>(filters.size() * sizeof(can_filter));
  const can_err_mask_t all_errors = CAN_ERR_MASK;
  const int enable = 1;
  if (::setsockopt(fd.get(), SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(), filter_bytes) != 0 ||
      ::setsockopt(fd.get(), SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &all_errors, sizeof all_errors) != 0 ||
      ::setsockopt(fd.get(), SOL_SOCKET, SO_RXQ_OVFL, &enable, sizeof enable) != 0) {
    return error_from_errno(errno, where, "cannot set socket options");
  }

  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = static_cast<int>(ifindex);
  if (::bind(fd.get(), reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    const int err = errno;
    if (err == ENODEV) {
      return make_error(ErrorCode::kInvalidArgument,
                        where + ": '" + config.interface + "' is not a CAN interface");
    }
    return error_from_errno(err, where, "cannot bind");
  }

  const bool controller = has_controller(config.interface);
  if (controller) warn_on_bitrate_mismatch(config, where);
  const CanBusState initial =
      interface_is_up(fd.get(), config.interface) ? CanBusState::kErrorActive : CanBusState::kDown;
  return std::unique_ptr<CanBus>(std::make_unique<SocketCanBus>(std::move(fd), config.interface, ifindex,
                                                                initial, controller, std::move(filters)));
}

}  // namespace hubrt::hal::socketcan
