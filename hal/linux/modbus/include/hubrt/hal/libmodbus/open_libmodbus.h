// The Linux Modbus backend: a ModbusClient on libmodbus 3.1 (RTU over a serial port, or TCP).
#pragma once

#include <memory>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/modbus_client.h"

namespace hubrt::hal::libmodbus {

// Opens a Modbus master for `config`.
//
// TCP: `host` must be an IPv4 address (no name lookup: a DNS query could block a reconnect in
// the cycle). The factory tries to connect once, bounded by the response timeout. When nobody
// answers (refused, timeout, unreachable) the client is still returned, disconnected: its calls
// fail fast with kUnavailable, and at most one call per `reconnect_interval` tries to connect
// again. A drive that boots after the hub is normal operation, not a configuration error.
// RTU: the serial device is opened and configured here; a device that does not exist or cannot
// be opened fails the factory, since that is a wiring or permission problem to fix.
// After a lost connection (reset, broken pipe, serial I/O error) both reconnect the same way.
// After a timeout or a mismatched answer, a TCP client closes the connection and the next call
// opens a fresh one at once (one connect attempt, so a call takes at most connect + response
// timeout): a late answer can then never be taken for the answer to a later request. An RTU
// client flushes the line before its next request; RTU has no transaction id, so an answer later
// than that flush cannot be told apart (use a response timeout the drive always meets).
//
// Errors: kInvalidArgument (host not IPv4, port 0, RTU unit id outside 1..247, parity not
// N/E/O, data bits outside 5..8, stop bits not 1/2, baud 0, response timeout not in (0, 1 h]),
// kNotFound (no such serial device), kPermissionDenied, kIo (e.g. not a serial port).
// Every message names config.device and the endpoint.
// The returned client is not thread-safe (one owner), like every ModbusClient.
Expected<std::unique_ptr<ModbusClient>> open_libmodbus(const ModbusConfig& config);

// The same, with the clock that paces reconnect attempts (tests pass a ManualClock).
// `clock` must outlive the client.
Expected<std::unique_ptr<ModbusClient>> open_libmodbus(const ModbusConfig& config, const Clock& clock);

}  // namespace hubrt::hal::libmodbus
