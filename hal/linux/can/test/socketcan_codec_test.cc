// The SocketCAN backend below its system calls: frame and filter conversion, error frames.
#include "socketcan_codec.h"

#include <vector>

#include <gtest/gtest.h>
#include <linux/can/error.h>
#include <linux/can/netlink.h>

namespace hubrt::hal::socketcan {
namespace {

CanFrame make(std::uint32_t id, bool extended, bool remote, std::uint8_t len) {
  CanFrame f;
  f.id = id;
  f.extended = extended;
  f.remote = remote;
  f.len = len;
  for (std::uint8_t i = 0; i < len; ++i) f.data[i] = static_cast<std::uint8_t>(0x10 + i);
  return f;
}

TEST(SocketCanCodec, StandardFrameMapsToKernelLayout) {
  can_frame k{};
  ASSERT_TRUE(to_kernel_frame(make(0x123, false, false, 3), k).is_ok());
  EXPECT_EQ(k.can_id, 0x123U);
  EXPECT_EQ(k.len, 3);
  EXPECT_EQ(k.data[0], 0x10);
  EXPECT_EQ(k.data[2], 0x12);
  EXPECT_EQ(k.data[3], 0) << "bytes past len are zero";
}

TEST(SocketCanCodec, ExtendedAndRemoteFlagsRoundTrip) {
  for (const CanFrame& f :
       {make(0x1ABCDE12, true, false, 8), make(0x7FF, false, true, 0), make(0, true, true, 2)}) {
    can_frame k{};
    ASSERT_TRUE(to_kernel_frame(f, k).is_ok());
    EXPECT_EQ((k.can_id & CAN_EFF_FLAG) != 0, f.extended);
    EXPECT_EQ((k.can_id & CAN_RTR_FLAG) != 0, f.remote);
    const CanFrame back = from_kernel_frame(k);
    EXPECT_EQ(back.id, f.id);
    EXPECT_EQ(back.extended, f.extended);
    EXPECT_EQ(back.remote, f.remote);
    EXPECT_EQ(back.len, f.len);
    if (!f.remote) {
      EXPECT_EQ(back.data, f.data);
    }
  }
}

TEST(SocketCanCodec, FramesTheKernelCannotCarryAreRejected) {
  can_frame k{};
  EXPECT_EQ(to_kernel_frame(make(0x1, false, false, 9), k).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(to_kernel_frame(make(0x800, false, false, 1), k).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(to_kernel_frame(make(0x2000'0000, true, false, 1), k).code(), ErrorCode::kInvalidArgument);
  EXPECT_TRUE(to_kernel_frame(make(0x1FFF'FFFF, true, false, 1), k).is_ok());
}

// The kernel's CAN_RAW_FILTER rule: a frame passes a filter when (can_id & mask) == (filter_id & mask).
bool kernel_passes(const std::vector<can_filter>& filters, const CanFrame& f) {
  can_frame k{};
  EXPECT_TRUE(to_kernel_frame(f, k).is_ok());
  for (const can_filter& flt : filters) {
    if ((k.can_id & flt.can_mask) == (flt.can_id & flt.can_mask)) return true;
  }
  return false;
}

TEST(SocketCanCodec, KernelFiltersFollowTheHalRule) {
  std::vector<can_filter> k;
  const std::vector<CanFilter> hal{CanFilter{0x100, 0x700, false}, CanFilter{0x1000, 0x1FFF'F000, true}};
  ASSERT_TRUE(to_kernel_filters(hal, k).is_ok());
  ASSERT_EQ(k.size(), 2U);
  EXPECT_TRUE(kernel_passes(k, make(0x105, false, false, 1)));
  EXPECT_TRUE(kernel_passes(k, make(0x1FF, false, true, 0))) << "remote frames pass like data frames";
  EXPECT_FALSE(kernel_passes(k, make(0x205, false, false, 1)));
  EXPECT_FALSE(kernel_passes(k, make(0x105, true, false, 1))) << "the frame format must match";
  EXPECT_TRUE(kernel_passes(k, make(0x1ABC, true, false, 1)));
  EXPECT_FALSE(kernel_passes(k, make(0x2ABC, true, false, 1)));
  EXPECT_FALSE(kernel_passes(k, make(0x1ABC & 0x7FF, false, false, 1)));
}

TEST(SocketCanCodec, NoFiltersMeansEverythingNotNothing) {
  std::vector<can_filter> k{can_filter{1, 1}};
  ASSERT_TRUE(to_kernel_filters({}, k).is_ok());
  ASSERT_EQ(k.size(), 1U);
  EXPECT_TRUE(kernel_passes(k, make(0x123, false, false, 0)));
  EXPECT_TRUE(kernel_passes(k, make(0x1234567, true, false, 0)));
}

TEST(SocketCanCodec, InvalidFiltersAreRejected) {
  std::vector<can_filter> k;
  const std::vector<CanFilter> wide{CanFilter{0x800, 0x7FF, false}};
  EXPECT_EQ(to_kernel_filters(wide, k).code(), ErrorCode::kInvalidArgument);
  const std::vector<CanFilter> too_many(CAN_RAW_FILTER_MAX + 1, CanFilter{});
  EXPECT_EQ(to_kernel_filters(too_many, k).code(), ErrorCode::kInvalidArgument);
}

can_frame error_frame(canid_t classes) {
  can_frame f{};
  f.can_id = CAN_ERR_FLAG | classes;
  f.len = CAN_ERR_DLC;
  return f;
}

TEST(SocketCanCodec, ControllerErrorFramesMoveTheState) {
  CanBusStatus s;
  can_frame warning = error_frame(CAN_ERR_CRTL);
  warning.data[1] = CAN_ERR_CRTL_TX_WARNING;
  apply_error_frame(warning, s);
  EXPECT_EQ(s.state, CanBusState::kErrorWarning);

  can_frame passive = error_frame(CAN_ERR_CRTL | CAN_ERR_CNT);
  passive.data[1] = CAN_ERR_CRTL_RX_PASSIVE;
  passive.data[6] = 12;
  passive.data[7] = 130;
  apply_error_frame(passive, s);
  EXPECT_EQ(s.state, CanBusState::kErrorPassive);
  EXPECT_EQ(s.tx_errors, 12);
  EXPECT_EQ(s.rx_errors, 130);

  apply_error_frame(error_frame(CAN_ERR_BUSOFF), s);
  EXPECT_EQ(s.state, CanBusState::kBusOff);
  apply_error_frame(error_frame(CAN_ERR_RESTARTED), s);
  EXPECT_EQ(s.state, CanBusState::kErrorActive);

  can_frame recovered = error_frame(CAN_ERR_CRTL);
  recovered.data[1] = CAN_ERR_CRTL_ACTIVE;
  s.state = CanBusState::kErrorPassive;
  apply_error_frame(recovered, s);
  EXPECT_EQ(s.state, CanBusState::kErrorActive);
  EXPECT_EQ(s.error_frames, 5U);
}

TEST(SocketCanCodec, BusOffWinsWithinOneFrameAndOtherClassesOnlyCount) {
  CanBusStatus s;
  can_frame both = error_frame(CAN_ERR_CRTL | CAN_ERR_BUSOFF);
  both.data[1] = CAN_ERR_CRTL_TX_PASSIVE;
  apply_error_frame(both, s);
  EXPECT_EQ(s.state, CanBusState::kBusOff);

  CanBusStatus t;
  apply_error_frame(error_frame(CAN_ERR_PROT | CAN_ERR_ACK | CAN_ERR_LOSTARB), t);
  EXPECT_EQ(t.state, CanBusState::kErrorActive);
  EXPECT_EQ(t.error_frames, 1U);
}

TEST(SocketCanCodec, NetlinkStatesMap) {
  EXPECT_EQ(from_netlink_state(CAN_STATE_ERROR_ACTIVE), CanBusState::kErrorActive);
  EXPECT_EQ(from_netlink_state(CAN_STATE_ERROR_WARNING), CanBusState::kErrorWarning);
  EXPECT_EQ(from_netlink_state(CAN_STATE_ERROR_PASSIVE), CanBusState::kErrorPassive);
  EXPECT_EQ(from_netlink_state(CAN_STATE_BUS_OFF), CanBusState::kBusOff);
  EXPECT_EQ(from_netlink_state(CAN_STATE_STOPPED), CanBusState::kDown);
}

}  // namespace
}  // namespace hubrt::hal::socketcan
