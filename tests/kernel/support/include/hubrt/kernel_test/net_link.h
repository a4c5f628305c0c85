// Taking a network interface (vcan0) down and up from a test, as a cable pull or a bus-off
// recovery would. Needs CAP_NET_ADMIN: root in the kernel tier's guest.
#pragma once

#include <string>

#include "hubrt/base/status.h"

namespace hubrt::kernel_test {

// Sets or clears IFF_UP on `ifname` (SIOCSIFFLAGS). Errors: kNotFound for an unknown interface,
// kPermissionDenied without CAP_NET_ADMIN, kIo otherwise; messages name the interface.
// Thread-safe.
Expected<void> set_link_up(const std::string& ifname, bool up);

// Whether IFF_UP is set on `ifname`. Errors as set_link_up(). Thread-safe.
Expected<bool> is_link_up(const std::string& ifname);

}  // namespace hubrt::kernel_test
