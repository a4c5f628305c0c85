// HttpClient on cpp-httplib (Debian's libcpp-httplib-dev, 0.11): plain HTTP/1.1, one connection
// per request (a platform that rebooted or a server that came back is simply connected again).
#pragma once

#include <memory>

#include "hubrt/base/status.h"
#include "hubrt/hal/http_client.h"

namespace hubrt::hal::httplib_client {

// A client for `config` (nothing is connected until the first send()).
// Errors: kInvalidArgument (empty host, port 0, timeouts not positive, a base path that does not
// start with '/', an authorization value with a line break), naming the device.
Expected<std::unique_ptr<HttpClient>> open_httplib(const HttpConfig& config);

}  // namespace hubrt::hal::httplib_client
