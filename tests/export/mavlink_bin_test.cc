#include "export/mavlink_bin.h"

#include <cmath>

#include <gtest/gtest.h>

namespace cinepath::exporter {
namespace {

std::string Hex(const std::string& bytes) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (unsigned char c : bytes) {
    out += digits[c >> 4];
    out += digits[c & 15];
  }
  return out;
}

TEST(MavlinkBin, X25CheckValue) {
  // CRC-16/MCRF4XX check value for "123456789".
  EXPECT_EQ(X25Accumulate(0xFFFF, "123456789"), 0x6F91);
}

TEST(MavlinkBin, MatchesNodeMavlinkTestVector) {
  // docs/mission-formats.md §3.2: node-mavlink 2.3.0 serialization of one MISSION_ITEM_INT.
  MavItem item;
  item.command = 16;
  item.frame = 3;
  item.params = {0, 0, 0, std::nan(""), 47.3977419, 8.545594, 50};
  item.autocontinue = true;
  const std::string frame = FrameMavlink2(0, 255, 190, 73, MissionItemIntPayload(item, 1, false), 38);
  EXPECT_EQ(Hex(frame),
            "fd25000000ffbe4900000000000000000000000000000000c07f4b52401c44f41705000048420100100001010300014b0e");
}

TEST(MavlinkBin, StreamStartsWithMissionCount) {
  Mission mission;
  mission.home = {47.0, 8.0, 400.0, 447.0};
  MavMission items;
  MavItem wp;
  wp.command = 16;
  wp.frame = 3;
  wp.params = {0, 0, 0, 90, 47.001, 8.001, 20};
  items.items = {wp, wp};
  const std::string px4 = WriteMavlinkBin(mission, items, Firmware::kPx4);
  // MISSION_COUNT: count 2, target 1/1, mission_type 0 truncated → 4-byte payload.
  ASSERT_GE(px4.size(), 16u);
  EXPECT_EQ(static_cast<unsigned char>(px4[0]), 0xFD);
  EXPECT_EQ(px4[1], 4);
  EXPECT_EQ(static_cast<unsigned char>(px4[7]), 44);
  EXPECT_EQ(px4[10], 2);  // count low byte
  // ArduPilot reserves seq 0 for home: one item more.
  const std::string ardupilot = WriteMavlinkBin(mission, items, Firmware::kArduPilot);
  EXPECT_EQ(ardupilot[10], 3);
  EXPECT_GT(ardupilot.size(), px4.size());
}

TEST(MavlinkBin, MissionFrameCoordinatesAreUnscaled) {
  MavItem gimbal;
  gimbal.command = 1000;
  gimbal.frame = 2;
  gimbal.params = {-30, 10, 0, 0, 16, 0, 0};  // flags 16 in param5 stay 16, not 16e7
  const std::string p = MissionItemIntPayload(gimbal, 5, false);
  ASSERT_EQ(p.size(), 38u);
  int32_t x;
  std::memcpy(&x, p.data() + 16, 4);
  EXPECT_EQ(x, 16);
}

}  // namespace
}  // namespace cinepath::exporter
