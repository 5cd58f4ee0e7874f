// A MAVLink 2 byte stream for tools that upload directly: one MISSION_COUNT (msg 44) followed by one
// MISSION_ITEM_INT (msg 73) per item, as a ground station sends them during the mission upload
// protocol (docs/mission-formats.md §3.2). Sender sysid 255 / compid 190, target 1/1, packet sequence from 0,
// unsigned frames, trailing zero bytes of each payload truncated (MAVLink 2 rule). For ArduPilot,
// seq 0 is the home item; for PX4 the first mission item is seq 0.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "export/mavlink_mission.h"
#include "export/mission.h"

namespace cinepath::exporter {

namespace mavlink_wire {
constexpr uint8_t kMagicV2 = 0xFD;
constexpr uint32_t kMsgMissionCount = 44;
constexpr uint8_t kCrcExtraMissionCount = 221;
constexpr uint32_t kMsgMissionItemInt = 73;
constexpr uint8_t kCrcExtraMissionItemInt = 38;
constexpr uint8_t kSenderSystem = 255;
constexpr uint8_t kSenderComponent = 190;
constexpr uint8_t kTargetSystem = 1;
constexpr uint8_t kTargetComponent = 1;
}  // namespace mavlink_wire

// X.25 / CRC-16-MCRF4XX as MAVLink uses it (init 0xFFFF).
uint16_t X25Accumulate(uint16_t crc, std::string_view bytes);

// One framed MAVLink 2 packet: header, payload (trailing zeros truncated, at least one byte kept),
// checksum over header-after-magic + payload + crc_extra.
std::string FrameMavlink2(uint8_t packet_seq, uint8_t sysid, uint8_t compid, uint32_t msgid, std::string payload,
                          uint8_t crc_extra);

// MISSION_ITEM_INT payload (38 bytes, wire order). x/y are degE7 for global frames, unscaled otherwise.
std::string MissionItemIntPayload(const MavItem& item, uint16_t seq, bool current);

// The whole stream: MISSION_COUNT then every item.
std::string WriteMavlinkBin(const Mission& mission, const MavMission& items, Firmware firmware);

}  // namespace cinepath::exporter
