#include "hubrt/dds/retcode.h"

#include <gtest/gtest.h>

namespace hubrt::dds {
namespace {

TEST(Retcode, NonNegativeValuesAreSuccess) {
  EXPECT_TRUE(to_status(DDS_RETCODE_OK).is_ok());
  EXPECT_TRUE(to_status(12345).is_ok());  // entity handles and counts share the type
}

TEST(Retcode, NamesAreTheCycloneMacroNames) {
  EXPECT_EQ(retcode_name(DDS_RETCODE_BAD_PARAMETER), "DDS_RETCODE_BAD_PARAMETER");
  EXPECT_EQ(retcode_name(DDS_RETCODE_TIMEOUT), "DDS_RETCODE_TIMEOUT");
  EXPECT_EQ(retcode_name(DDS_RETCODE_NOT_FOUND), "DDS_RETCODE_NOT_FOUND");
  EXPECT_EQ(retcode_name(-999), "DDS_RETCODE_UNKNOWN");
}

TEST(Retcode, ErrorMessageSaysWhatWasDoneAndExplainsTheCode) {
  const Error e = dds_error(DDS_RETCODE_TIMEOUT, "wait for 'rt/dock/state'");
  EXPECT_EQ(e.code, ErrorCode::kTimeout);
  EXPECT_EQ(e.message, std::string("wait for 'rt/dock/state': DDS_RETCODE_TIMEOUT (") +
                           dds_strretcode(DDS_RETCODE_TIMEOUT) + ")");
  const Error bad = dds_error(DDS_RETCODE_BAD_PARAMETER, "create reader on 'rt/dock/command'");
  EXPECT_EQ(
      bad.message.rfind("create reader on 'rt/dock/command': DDS_RETCODE_BAD_PARAMETER (Bad Parameter)", 0),
      0u)
      << bad.message;
  EXPECT_NE(bad.message.find("deleted"), std::string::npos) << bad.message;
}

}  // namespace
}  // namespace hubrt::dds
