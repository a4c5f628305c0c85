#include "modbus_errors.h"

#include <cerrno>

#include <gtest/gtest.h>
#include <modbus/modbus.h>

namespace hubrt::hal::libmodbus {
namespace {

TEST(ModbusErrors, TimeoutKeepsTheConnectionButFlushes) {
  const ModbusFailure f = classify_modbus_errno(ETIMEDOUT);
  EXPECT_EQ(f.code, ErrorCode::kTimeout);
  EXPECT_FALSE(f.connection_lost);
  EXPECT_TRUE(f.flush_before_next);
}

TEST(ModbusErrors, ExceptionResponsesAreProtocolErrorsWithTheirName) {
  for (const int err : {EMBXILFUN, EMBXILADD, EMBXILVAL, EMBXSFAIL, EMBXSBUSY}) {
    const ModbusFailure f = classify_modbus_errno(err);
    EXPECT_EQ(f.code, ErrorCode::kProtocol) << err;
    EXPECT_FALSE(f.connection_lost) << err;
    EXPECT_FALSE(modbus_exception_name(err).empty()) << err;
  }
  EXPECT_EQ(modbus_exception_name(EMBXILADD), "illegal data address (exception 02)");
  EXPECT_EQ(modbus_exception_name(EMBXILVAL), "illegal data value (exception 03)");
  EXPECT_TRUE(modbus_exception_name(ETIMEDOUT).empty());
}

TEST(ModbusErrors, MalformedAnswersAreProtocolErrorsAndFlush) {
  for (const int err : {EMBBADCRC, EMBBADDATA, EMBBADEXC, EMBBADSLAVE}) {
    const ModbusFailure f = classify_modbus_errno(err);
    EXPECT_EQ(f.code, ErrorCode::kProtocol) << err;
    EXPECT_TRUE(f.flush_before_next) << err;
  }
}

TEST(ModbusErrors, GatewayCannotReachTheUnit) {
  EXPECT_EQ(classify_modbus_errno(EMBXGTAR).code, ErrorCode::kUnavailable);
  EXPECT_FALSE(classify_modbus_errno(EMBXGTAR).connection_lost);
}

TEST(ModbusErrors, BrokenLinksAreUnavailableAndReconnect) {
  for (const int err : {ECONNRESET, ECONNREFUSED, EPIPE, ENOTCONN, EBADF, EIO}) {
    const ModbusFailure f = classify_modbus_errno(err);
    EXPECT_EQ(f.code, ErrorCode::kUnavailable) << err;
    EXPECT_TRUE(f.connection_lost) << err;
  }
  EXPECT_EQ(classify_modbus_errno(EINVAL).code, ErrorCode::kInvalidArgument);
  const ModbusFailure unknown = classify_modbus_errno(ENOMEM);
  EXPECT_EQ(unknown.code, ErrorCode::kIo);
  EXPECT_TRUE(unknown.connection_lost) << "an unknown failure leaves the link in an unknown state";
}

}  // namespace
}  // namespace hubrt::hal::libmodbus
