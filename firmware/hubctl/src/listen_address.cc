#include "listen_address.h"

#include <stdexcept>

#include <fmt/format.h>

namespace hubrt::hubctl {

Expected<ListenEndpoint> parse_listen(const std::string& text) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0)
    return make_error(ErrorCode::kInvalidArgument, fmt::format("--listen '{}': expected ADDR:PORT", text));
  ListenEndpoint e;
  e.address = text.substr(0, colon);
  if (e.address.size() > 2 && e.address.front() == '[' && e.address.back() == ']')
    e.address = e.address.substr(1, e.address.size() - 2);
  try {
    std::size_t used = 0;
    e.port = std::stoi(text.substr(colon + 1), &used);
    if (used != text.size() - colon - 1 || e.port < 0 || e.port > 65535) throw std::out_of_range("port");
  } catch (const std::exception&) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("--listen '{}': bad port", text));
  }
  return e;
}

bool host_allowed(std::string_view host, std::string_view listen_address, std::uint16_t port) {
  const bool loopback = listen_address == "127.0.0.1" || listen_address == "localhost" ||
                        listen_address == "::1" || listen_address.starts_with("127.");
  if (!loopback) return !host.empty();
  for (const std::string& allowed :
       {fmt::format("127.0.0.1:{}", port), fmt::format("localhost:{}", port), fmt::format("[::1]:{}", port),
        fmt::format("{}:{}", listen_address, port)})
    if (host == allowed) return true;
  return false;
}

}  // namespace hubrt::hubctl
