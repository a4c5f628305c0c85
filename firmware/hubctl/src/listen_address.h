// Where hubctl's servers (serve: the operator screen; foxglove: the Foxglove WebSocket) listen, and
// which Host headers they answer.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "hubrt/base/status.h"

namespace hubrt::hubctl {

struct ListenEndpoint {
  std::string address;  // "127.0.0.1", "::1" (written "[::1]:PORT"), "0.0.0.0"
  int port = 0;         // 0: a free one
};

// "ADDR:PORT" as --listen takes it. Errors: kInvalidArgument naming the option's text (no colon,
// port not a number in 0..65535). Thread-safe.
Expected<ListenEndpoint> parse_listen(const std::string& text);

// A Host header the server answers: with a loopback listen address only "127.0.0.1:<port>",
// "localhost:<port>" and "[::1]:<port>" (a DNS-rebinding page sends its own name); with any other
// address, any host. Thread-safe.
bool host_allowed(std::string_view host, std::string_view listen_address, std::uint16_t port);

}  // namespace hubrt::hubctl
