#include "export/mavlink_bin.h"

#include <cmath>
#include <cstring>

#include "core/error.h"

namespace cinepath::exporter {

namespace {

void PutU8(std::string& out, uint8_t v) { out.push_back(static_cast<char>(v)); }
void PutU16(std::string& out, uint16_t v) {
  PutU8(out, v & 0xFF);
  PutU8(out, v >> 8);
}
void PutU32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) PutU8(out, (v >> (8 * i)) & 0xFF);
}
void PutF32(std::string& out, float v) {
  uint32_t bits;
  std::memcpy(&bits, &v, 4);
  PutU32(out, bits);
}
int32_t ScaledCoordinate(double value, bool global) {
  const double scaled = std::round(global ? value * 1e7 : value);
  CINEPATH_CHECK(std::isfinite(scaled) && std::abs(scaled) <= 2147483647.0);
  return static_cast<int32_t>(scaled);
}

}  // namespace

uint16_t X25Accumulate(uint16_t crc, std::string_view bytes) {
  for (char c : bytes) {
    uint8_t tmp = static_cast<uint8_t>(c) ^ static_cast<uint8_t>(crc & 0xFF);
    tmp ^= static_cast<uint8_t>(tmp << 4);
    crc = static_cast<uint16_t>((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4));
  }
  return crc;
}

std::string FrameMavlink2(uint8_t packet_seq, uint8_t sysid, uint8_t compid, uint32_t msgid, std::string payload,
                          uint8_t crc_extra) {
  while (payload.size() > 1 && payload.back() == '\0') payload.pop_back();
  std::string frame;
  PutU8(frame, mavlink_wire::kMagicV2);
  PutU8(frame, static_cast<uint8_t>(payload.size()));
  PutU8(frame, 0);  // incompat flags (unsigned)
  PutU8(frame, 0);  // compat flags
  PutU8(frame, packet_seq);
  PutU8(frame, sysid);
  PutU8(frame, compid);
  PutU8(frame, msgid & 0xFF);
  PutU8(frame, (msgid >> 8) & 0xFF);
  PutU8(frame, (msgid >> 16) & 0xFF);
  frame += payload;
  uint16_t crc = X25Accumulate(0xFFFF, std::string_view(frame).substr(1));
  const char extra = static_cast<char>(crc_extra);
  crc = X25Accumulate(crc, std::string_view(&extra, 1));
  PutU16(frame, crc);
  return frame;
}

std::string MissionItemIntPayload(const MavItem& item, uint16_t seq, bool current) {
  std::string p;
  for (int i = 0; i < 4; ++i) PutF32(p, static_cast<float>(item.params[i]));
  PutU32(p, static_cast<uint32_t>(ScaledCoordinate(item.params[4], item.IsGlobal())));
  PutU32(p, static_cast<uint32_t>(ScaledCoordinate(item.params[5], item.IsGlobal())));
  PutF32(p, static_cast<float>(item.params[6]));
  PutU16(p, seq);
  PutU16(p, static_cast<uint16_t>(item.command));
  PutU8(p, mavlink_wire::kTargetSystem);
  PutU8(p, mavlink_wire::kTargetComponent);
  PutU8(p, static_cast<uint8_t>(item.frame));
  PutU8(p, current ? 1 : 0);
  PutU8(p, item.autocontinue ? 1 : 0);
  PutU8(p, 0);  // mission_type MAV_MISSION_TYPE_MISSION (extension)
  return p;
}

std::string WriteMavlinkBin(const Mission& mission, const MavMission& items, Firmware firmware) {
  std::vector<MavItem> all;
  if (firmware == Firmware::kArduPilot) all.push_back(HomeItem(mission));
  all.insert(all.end(), items.items.begin(), items.items.end());
  CINEPATH_CHECK(all.size() <= 65535);

  std::string stream;
  uint8_t packet_seq = 0;
  std::string count;
  PutU16(count, static_cast<uint16_t>(all.size()));
  PutU8(count, mavlink_wire::kTargetSystem);
  PutU8(count, mavlink_wire::kTargetComponent);
  PutU8(count, 0);  // mission_type (extension)
  stream += FrameMavlink2(packet_seq++, mavlink_wire::kSenderSystem, mavlink_wire::kSenderComponent,
                          mavlink_wire::kMsgMissionCount, count, mavlink_wire::kCrcExtraMissionCount);
  for (size_t seq = 0; seq < all.size(); ++seq) {
    stream += FrameMavlink2(
        packet_seq++, mavlink_wire::kSenderSystem, mavlink_wire::kSenderComponent, mavlink_wire::kMsgMissionItemInt,
        MissionItemIntPayload(all[seq], static_cast<uint16_t>(seq), false), mavlink_wire::kCrcExtraMissionItemInt);
  }
  return stream;
}

}  // namespace cinepath::exporter
