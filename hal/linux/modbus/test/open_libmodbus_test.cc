// open_libmodbus(): configuration errors, RTU on a pseudo-terminal, TCP while nobody listens.
// No server thread here (see libmodbus_against_server_test.cc for that).
#include "hubrt/hal/libmodbus/open_libmodbus.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>

namespace hubrt::hal::libmodbus {
namespace {

using std::chrono::milliseconds;
using Steady = std::chrono::steady_clock;

ModbusConfig tcp(std::string host, std::uint16_t port) {
  ModbusConfig c;
  c.device = "lift_drive";
  c.endpoint = ModbusTcpEndpoint{std::move(host), port};
  c.response_timeout = milliseconds(50);
  return c;
}

ModbusConfig rtu(std::string device) {
  ModbusConfig c;
  c.device = "lift_drive";
  c.endpoint = ModbusRtuEndpoint{std::move(device), 19200, 'E', 8, 1};
  c.response_timeout = milliseconds(50);
  return c;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

void expect_invalid(const ModbusConfig& config, const std::string& why) {
  const auto client = open_libmodbus(config);
  ASSERT_FALSE(client.is_ok()) << why;
  EXPECT_EQ(client.error().code, ErrorCode::kInvalidArgument) << why << ": " << client.error().message;
  EXPECT_TRUE(contains(client.error().message, "lift_drive")) << client.error().message;
}

TEST(OpenLibmodbus, RejectsInvalidConfiguration) {
  expect_invalid(tcp("lift.local", 502), "host name");
  expect_invalid(tcp("127.0.0.1", 0), "port 0");
  ModbusConfig no_timeout = tcp("127.0.0.1", 502);
  no_timeout.response_timeout = Duration::zero();
  expect_invalid(no_timeout, "zero timeout");
  ModbusConfig broadcast = rtu("/dev/ttyUSB0");
  broadcast.unit_id = 0;
  expect_invalid(broadcast, "RTU unit 0");
  ModbusConfig reserved = rtu("/dev/ttyUSB0");
  reserved.unit_id = 248;
  expect_invalid(reserved, "RTU unit 248");
  ModbusConfig parity = rtu("/dev/ttyUSB0");
  std::get<ModbusRtuEndpoint>(parity.endpoint).parity = 'X';
  expect_invalid(parity, "parity");
  ModbusConfig bits = rtu("/dev/ttyUSB0");
  std::get<ModbusRtuEndpoint>(bits.endpoint).data_bits = 9;
  expect_invalid(bits, "data bits");
  ModbusConfig stops = rtu("/dev/ttyUSB0");
  std::get<ModbusRtuEndpoint>(stops.endpoint).stop_bits = 3;
  expect_invalid(stops, "stop bits");

  const auto host = open_libmodbus(tcp("lift.local", 502));
  EXPECT_TRUE(contains(host.error().message, "IPv4")) << host.error().message;
}

TEST(OpenLibmodbus, MissingSerialDeviceIsNotFound) {
  const auto client = open_libmodbus(rtu("/dev/hubrt-no-such-tty"));
  ASSERT_FALSE(client.is_ok());
  EXPECT_EQ(client.error().code, ErrorCode::kNotFound);
  EXPECT_TRUE(contains(client.error().message, "/dev/hubrt-no-such-tty")) << client.error().message;
}

TEST(OpenLibmodbus, NonSerialDeviceIsAnIoError) {
  const auto client = open_libmodbus(rtu("/dev/null"));
  ASSERT_FALSE(client.is_ok());
  EXPECT_EQ(client.error().code, ErrorCode::kIo);
  EXPECT_TRUE(contains(client.error().message, "not a serial port")) << client.error().message;
}

// A pseudo-terminal stands in for the RS-485 adapter: the client configures it and sends a real
// RTU frame; nobody answers, so the call ends with kTimeout after the response timeout.
TEST(OpenLibmodbus, RtuSendsTheRequestAndTimesOutWhenNobodyAnswers) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(::grantpt(master), 0);
  ASSERT_EQ(::unlockpt(master), 0);
  std::array<char, 128> name{};
  ASSERT_EQ(::ptsname_r(master, name.data(), name.size()), 0);

  ModbusConfig config = rtu(name.data());
  config.unit_id = 5;
  auto client = open_libmodbus(config);
  ASSERT_TRUE(client.is_ok()) << client.error().message;

  std::array<std::uint16_t, 2> regs{};
  const auto start = Steady::now();
  EXPECT_EQ((*client)->read_holding_registers(0x0102, regs).code(), ErrorCode::kTimeout);
  const auto took = Steady::now() - start;
  EXPECT_GE(took, milliseconds(49)) << "the response timeout, not earlier";
  EXPECT_LT(took, std::chrono::seconds(2)) << "bounded by the timeout (2 s absorbs scheduling noise)";

  pollfd p{master, POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, 1000), 1);
  std::array<std::uint8_t, 16> wire{};
  const ssize_t n = ::read(master, wire.data(), wire.size());
  ASSERT_EQ(n, 8) << "unit, function, address, count, CRC";
  EXPECT_EQ(wire[0], 5);
  EXPECT_EQ(wire[1], 0x03);
  EXPECT_EQ(wire[2], 0x01);
  EXPECT_EQ(wire[3], 0x02);
  EXPECT_EQ(wire[5], 0x02);
  client->reset();
  ::close(master);
}

std::uint16_t unused_loopback_port() {
  const int s = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(::bind(s, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  socklen_t len = sizeof addr;
  ::getsockname(s, reinterpret_cast<sockaddr*>(&addr), &len);
  ::close(s);  // bound but never listening: connects to it are refused
  return ntohs(addr.sin_port);
}

TEST(OpenLibmodbus, TcpOpensWhileNobodyListensAndRetriesAtItsPace) {
  ManualClock clock;
  ModbusConfig config = tcp("127.0.0.1", unused_loopback_port());
  config.reconnect_interval = milliseconds(500);
  auto client = open_libmodbus(config, clock);
  ASSERT_TRUE(client.is_ok()) << "a drive that boots later is not a configuration error";

  std::array<std::uint16_t, 1> reg{};
  EXPECT_EQ((*client)->read_input_registers(0, reg).code(), ErrorCode::kUnavailable);
  clock.advance(milliseconds(500));
  EXPECT_EQ((*client)->read_input_registers(0, reg).code(), ErrorCode::kUnavailable)
      << "retried, still refused";
  EXPECT_EQ((*client)->write_register(0, 1).code(), ErrorCode::kUnavailable);
}

TEST(OpenLibmodbus, RequestsBeyondOnePduAreRefusedLocally) {
  ManualClock clock;
  auto client = open_libmodbus(tcp("127.0.0.1", unused_loopback_port()), clock);
  ASSERT_TRUE(client.is_ok());
  std::array<std::uint16_t, 126> too_many{};
  EXPECT_EQ((*client)->read_holding_registers(0, too_many).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ((*client)->read_holding_registers(0, std::span<std::uint16_t>()).code(),
            ErrorCode::kInvalidArgument);
  std::array<std::uint16_t, 2> two{};
  EXPECT_EQ((*client)->read_input_registers(0xFFFF, two).code(), ErrorCode::kInvalidArgument);
  std::array<std::uint16_t, 124> write_too_many{};
  EXPECT_EQ((*client)->write_registers(0, write_too_many).code(), ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace hubrt::hal::libmodbus
