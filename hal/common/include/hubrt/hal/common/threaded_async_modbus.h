// AsyncModbus on a worker thread of its own around any blocking ModbusClient (libmodbus on Linux,
// the same client against the fake backend's simulator server), so every backend gets it.
#pragma once

#include <memory>
#include <string>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/async_modbus.h"
#include "hubrt/hal/modbus_client.h"

namespace hubrt::hal {

// A request timeout that covers one batch on `config`: a connect attempt (the libmodbus client
// bounds a TCP connect by the response timeout) plus the write and the read, each bounded by the
// response timeout — three response timeouts.
[[nodiscard]] Duration batch_request_timeout(const ModbusConfig& config) noexcept;

// "lift_drive (tcp 127.0.0.1:1502, unit 1)" / "lift_drive (rtu /dev/ttyUSB0, unit 1)".
[[nodiscard]] std::string describe_modbus(const ModbusConfig& config);

// Starts a worker thread that owns `client` and runs the submitted requests on it (see
// AsyncModbus for the rules). `request_timeout`: the deadline after submit() at which poll()
// reports a request as timed out. `description` names the device in messages.
// Errors (the message names the device): kInvalidArgument (no client, request_timeout not
// positive), kUnavailable (the thread could not be started).
Expected<std::unique_ptr<AsyncModbus>> open_threaded_async_modbus(std::unique_ptr<ModbusClient> client,
                                                                  Duration request_timeout,
                                                                  std::string description);

}  // namespace hubrt::hal
