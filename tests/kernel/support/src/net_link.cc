#include "hubrt/kernel_test/net_link.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>

namespace hubrt::kernel_test {
namespace {

Error link_error(const std::string& ifname, const char* what, int error) {
  ErrorCode code = ErrorCode::kIo;
  if (error == ENODEV) code = ErrorCode::kNotFound;
  if (error == EPERM || error == EACCES) code = ErrorCode::kPermissionDenied;
  return make_error(code,
                    "interface " + ifname + ": " + what + ": " + std::generic_category().message(error));
}

// Interface flags go through any socket's ioctl; an AF_INET datagram socket is always there.
class IoctlSocket {
 public:
  IoctlSocket() : fd_(::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0)) {}
  IoctlSocket(const IoctlSocket&) = delete;
  IoctlSocket& operator=(const IoctlSocket&) = delete;
  ~IoctlSocket() {
    if (fd_ >= 0) ::close(fd_);
  }
  [[nodiscard]] int fd() const { return fd_; }

 private:
  int fd_;
};

Expected<ifreq> read_flags(const IoctlSocket& socket, const std::string& ifname) {
  if (socket.fd() < 0) return link_error(ifname, "socket", errno);
  if (ifname.empty() || ifname.size() >= IFNAMSIZ) {
    return make_error(ErrorCode::kInvalidArgument, "interface name '" + ifname + "' is empty or too long");
  }
  ifreq request{};
  std::memcpy(request.ifr_name, ifname.c_str(), ifname.size() + 1);
  if (::ioctl(socket.fd(), SIOCGIFFLAGS, &request) != 0) return link_error(ifname, "SIOCGIFFLAGS", errno);
  return request;
}

}  // namespace

Expected<void> set_link_up(const std::string& ifname, bool up) {
  IoctlSocket socket;
  auto request = read_flags(socket, ifname);
  if (!request) return std::move(request).error();
  if (up) {
    request->ifr_flags = static_cast<short>(request->ifr_flags | IFF_UP);
  } else {
    request->ifr_flags = static_cast<short>(request->ifr_flags & ~IFF_UP);
  }
  if (::ioctl(socket.fd(), SIOCSIFFLAGS, &*request) != 0) return link_error(ifname, "SIOCSIFFLAGS", errno);
  return {};
}

Expected<bool> is_link_up(const std::string& ifname) {
  IoctlSocket socket;
  auto request = read_flags(socket, ifname);
  if (!request) return std::move(request).error();
  return (request->ifr_flags & IFF_UP) != 0;
}

}  // namespace hubrt::kernel_test
