#include "devices/apt/apt_message.h"

#include <cstdio>

namespace fovea::apt {

bool addr::plausible(std::uint8_t a) {
  return a == kHost || a == kRack || a == kGenericUsb || (a >= kBay0 && a <= kBay0 + 9);
}

namespace {

struct Known {
  std::uint16_t id;
  std::uint16_t length;  // data bytes; 0 = header-only
  const char* name;
};

// Lengths from the protocol document's data-structure tables.
constexpr Known kKnown[] = {
    {id::kHwDisconnect, 0, "HW_DISCONNECT"},
    {id::kHwReqInfo, 0, "HW_REQ_INFO"},
    {id::kHwGetInfo, 84, "HW_GET_INFO"},
    {id::kHwStartUpdateMsgs, 0, "HW_START_UPDATEMSGS"},
    {id::kHwStopUpdateMsgs, 0, "HW_STOP_UPDATEMSGS"},
    {id::kHwResponse, 0, "HW_RESPONSE"},
    {id::kHwRichResponse, 68, "HW_RICHRESPONSE"},
    {id::kModSetChanEnableState, 0, "MOD_SET_CHANENABLESTATE"},
    {id::kModReqChanEnableState, 0, "MOD_REQ_CHANENABLESTATE"},
    {id::kModGetChanEnableState, 0, "MOD_GET_CHANENABLESTATE"},
    {id::kModIdentify, 0, "MOD_IDENTIFY"},
    {id::kMotSetVelParams, 14, "MOT_SET_VELPARAMS"},
    {id::kMotReqVelParams, 0, "MOT_REQ_VELPARAMS"},
    {id::kMotGetVelParams, 14, "MOT_GET_VELPARAMS"},
    {id::kMotSetJogParams, 22, "MOT_SET_JOGPARAMS"},
    {id::kMotReqJogParams, 0, "MOT_REQ_JOGPARAMS"},
    {id::kMotGetJogParams, 22, "MOT_GET_JOGPARAMS"},
    {id::kMotSetLimSwitchParams, 16, "MOT_SET_LIMSWITCHPARAMS"},
    {id::kMotReqLimSwitchParams, 0, "MOT_REQ_LIMSWITCHPARAMS"},
    {id::kMotGetLimSwitchParams, 16, "MOT_GET_LIMSWITCHPARAMS"},
    {id::kMotSetHomeParams, 14, "MOT_SET_HOMEPARAMS"},
    {id::kMotReqHomeParams, 0, "MOT_REQ_HOMEPARAMS"},
    {id::kMotGetHomeParams, 14, "MOT_GET_HOMEPARAMS"},
    {id::kMotSetMoveRelParams, 6, "MOT_SET_MOVERELPARAMS"},
    {id::kMotReqMoveRelParams, 0, "MOT_REQ_MOVERELPARAMS"},
    {id::kMotGetMoveRelParams, 6, "MOT_GET_MOVERELPARAMS"},
    {id::kMotSetMoveAbsParams, 6, "MOT_SET_MOVEABSPARAMS"},
    {id::kMotReqMoveAbsParams, 0, "MOT_REQ_MOVEABSPARAMS"},
    {id::kMotGetMoveAbsParams, 6, "MOT_GET_MOVEABSPARAMS"},
    {id::kMotMoveHome, 0, "MOT_MOVE_HOME"},
    {id::kMotMoveHomed, 0, "MOT_MOVE_HOMED"},
    {id::kMotMoveRelative, 6, "MOT_MOVE_RELATIVE"},
    {id::kMotMoveAbsolute, 6, "MOT_MOVE_ABSOLUTE"},
    {id::kMotMoveCompleted, 14, "MOT_MOVE_COMPLETED"},
    {id::kMotMoveStop, 0, "MOT_MOVE_STOP"},
    {id::kMotMoveStopped, 14, "MOT_MOVE_STOPPED"},
    {id::kMotMoveJog, 0, "MOT_MOVE_JOG"},
    {id::kMotReqStatusUpdate, 0, "MOT_REQ_STATUSUPDATE"},
    {id::kMotGetStatusUpdate, 14, "MOT_GET_STATUSUPDATE"},
    {id::kMotReqDcStatusUpdate, 0, "MOT_REQ_DCSTATUSUPDATE"},
    {id::kMotGetDcStatusUpdate, 14, "MOT_GET_DCSTATUSUPDATE"},
    {id::kMotAckDcStatusUpdate, 0, "MOT_ACK_DCSTATUSUPDATE"},
};

const Known* find(std::uint16_t message_id) {
  for (const auto& k : kKnown)
    if (k.id == message_id) return &k;
  return nullptr;
}

// Little-endian writers/readers over a data packet.
void put16(std::vector<std::uint8_t>& d, std::uint16_t v) {
  d.push_back(static_cast<std::uint8_t>(v & 0xFF));
  d.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put32(std::vector<std::uint8_t>& d, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) d.push_back(static_cast<std::uint8_t>((v >> (8 * i)) & 0xFF));
}
void putS32(std::vector<std::uint8_t>& d, std::int32_t v) {
  put32(d, static_cast<std::uint32_t>(v));
}
void putText(std::vector<std::uint8_t>& d, const std::string& s, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) d.push_back(i < s.size() ? static_cast<std::uint8_t>(s[i]) : 0);
}
std::uint16_t get16(const std::vector<std::uint8_t>& d, std::size_t at) {
  return static_cast<std::uint16_t>(d[at] | (d[at + 1] << 8));
}
std::uint32_t get32(const std::vector<std::uint8_t>& d, std::size_t at) {
  return static_cast<std::uint32_t>(d[at]) | (static_cast<std::uint32_t>(d[at + 1]) << 8) |
         (static_cast<std::uint32_t>(d[at + 2]) << 16) | (static_cast<std::uint32_t>(d[at + 3]) << 24);
}
std::int32_t getS32(const std::vector<std::uint8_t>& d, std::size_t at) {
  return static_cast<std::int32_t>(get32(d, at));
}
std::string getText(const std::vector<std::uint8_t>& d, std::size_t at, std::size_t n) {
  std::string s;
  for (std::size_t i = 0; i < n && d[at + i] != 0; ++i) s.push_back(static_cast<char>(d[at + i]));
  return s;
}

Message shortMsg(std::uint16_t message_id, std::uint8_t p1, std::uint8_t p2, std::uint8_t dest, std::uint8_t source) {
  Message m;
  m.id = message_id;
  m.param1 = p1;
  m.param2 = p2;
  m.dest = dest;
  m.source = source;
  return m;
}
Message longMsg(std::uint16_t message_id, std::vector<std::uint8_t> data, std::uint8_t dest, std::uint8_t source) {
  Message m;
  m.id = message_id;
  m.dest = dest;
  m.source = source;
  m.data = std::move(data);
  return m;
}

std::vector<std::uint8_t> statusData(const ChannelStatus& s, bool stepper) {
  std::vector<std::uint8_t> d;
  put16(d, s.channel);
  putS32(d, s.position);
  if (stepper) {
    putS32(d, s.velocity_or_encoder);
  } else {
    put16(d, static_cast<std::uint16_t>(s.velocity_or_encoder & 0xFFFF));
    put16(d, 0);  // reserved (motor current on newer firmware)
  }
  put32(d, s.bits);
  return d;
}

std::optional<ChannelValue> parseChannelLong(const Message& m, std::uint16_t expected) {
  if (m.id != expected || m.data.size() != 6) return std::nullopt;
  return ChannelValue{get16(m.data, 0), getS32(m.data, 2)};
}

}  // namespace

std::optional<std::uint16_t> knownDataLength(std::uint16_t message_id) {
  if (const Known* k = find(message_id)) return k->length;
  return std::nullopt;
}

bool acceptsLength(std::uint16_t message_id, std::uint16_t data_length) {
  const Known* k = find(message_id);
  if (!k) return false;
  if (data_length == k->length) return true;
  // Older firmware sends these as header-only messages; newer ones append a status block.
  const bool either =
      message_id == id::kMotMoveCompleted || message_id == id::kMotMoveStopped || message_id == id::kMotMoveHomed;
  if (either) return data_length == 0 || data_length == 14;
  // Header-only moves by the stored MOVEABSPARAMS / MOVERELPARAMS.
  const bool move = message_id == id::kMotMoveAbsolute || message_id == id::kMotMoveRelative;
  return move && data_length == 0;
}

std::uint8_t channelIdent(int channel, bool bit_mask) {
  if (bit_mask && channel >= 1 && channel <= 8) return static_cast<std::uint8_t>(1u << (channel - 1));
  return static_cast<std::uint8_t>(channel);
}

std::string messageName(std::uint16_t message_id) {
  if (const Known* k = find(message_id)) return k->name;
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%04X", message_id);
  return buf;
}

std::vector<std::uint8_t> encode(const Message& m) {
  std::vector<std::uint8_t> out;
  out.reserve(6 + m.data.size());
  put16(out, m.id);
  if (m.data.empty()) {
    out.push_back(m.param1);
    out.push_back(m.param2);
    out.push_back(m.dest);
  } else {
    put16(out, static_cast<std::uint16_t>(m.data.size()));
    out.push_back(static_cast<std::uint8_t>(m.dest | addr::kDataFlag));
  }
  out.push_back(m.source);
  out.insert(out.end(), m.data.begin(), m.data.end());
  return out;
}

std::string toHex(std::span<const std::uint8_t> bytes) {
  static const char* digits = "0123456789ABCDEF";
  std::string s;
  s.reserve(bytes.size() * 3);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    if (i) s.push_back(' ');
    s.push_back(digits[bytes[i] >> 4]);
    s.push_back(digits[bytes[i] & 0xF]);
  }
  return s;
}

// ---- Host -> controller ----------------------------------------------------------------------
Message identify(std::uint8_t dest, std::uint8_t channel) {
  return shortMsg(id::kModIdentify, channel, 0, dest, addr::kHost);
}
Message reqHwInfo(std::uint8_t dest) {
  return shortMsg(id::kHwReqInfo, 0, 0, dest, addr::kHost);
}
Message setChanEnableState(std::uint8_t dest, std::uint8_t channel, bool enabled) {
  // Enable state byte: 0x01 enabled, 0x02 disabled.
  return shortMsg(id::kModSetChanEnableState, channel, enabled ? 0x01 : 0x02, dest, addr::kHost);
}
Message reqChanEnableState(std::uint8_t dest, std::uint8_t channel) {
  return shortMsg(id::kModReqChanEnableState, channel, 0, dest, addr::kHost);
}
Message startUpdateMsgs(std::uint8_t dest) {
  return shortMsg(id::kHwStartUpdateMsgs, 0, 0, dest, addr::kHost);
}
Message stopUpdateMsgs(std::uint8_t dest) {
  return shortMsg(id::kHwStopUpdateMsgs, 0, 0, dest, addr::kHost);
}
Message moveHome(std::uint8_t dest, std::uint8_t channel) {
  return shortMsg(id::kMotMoveHome, channel, 0, dest, addr::kHost);
}
Message moveAbsolute(std::uint8_t dest, std::uint16_t channel, std::int32_t position_counts) {
  std::vector<std::uint8_t> d;
  put16(d, channel);
  putS32(d, position_counts);
  return longMsg(id::kMotMoveAbsolute, std::move(d), dest, addr::kHost);
}
Message moveRelative(std::uint8_t dest, std::uint16_t channel, std::int32_t distance_counts) {
  std::vector<std::uint8_t> d;
  put16(d, channel);
  putS32(d, distance_counts);
  return longMsg(id::kMotMoveRelative, std::move(d), dest, addr::kHost);
}
Message moveJog(std::uint8_t dest, std::uint8_t channel, JogDirection direction) {
  return shortMsg(id::kMotMoveJog, channel, static_cast<std::uint8_t>(direction), dest, addr::kHost);
}
Message moveStop(std::uint8_t dest, std::uint8_t channel, StopMode mode) {
  return shortMsg(id::kMotMoveStop, channel, static_cast<std::uint8_t>(mode), dest, addr::kHost);
}
Message reqDcStatusUpdate(std::uint8_t dest, std::uint8_t channel) {
  return shortMsg(id::kMotReqDcStatusUpdate, channel, 0, dest, addr::kHost);
}
Message ackDcStatusUpdate(std::uint8_t dest) {
  return shortMsg(id::kMotAckDcStatusUpdate, 0, 0, dest, addr::kHost);
}
Message reqStatusUpdate(std::uint8_t dest, std::uint8_t channel) {
  return shortMsg(id::kMotReqStatusUpdate, channel, 0, dest, addr::kHost);
}
Message setVelParams(std::uint8_t dest, const VelParams& p) {
  std::vector<std::uint8_t> d;
  put16(d, p.channel);
  putS32(d, p.min_velocity);
  putS32(d, p.acceleration);
  putS32(d, p.max_velocity);
  return longMsg(id::kMotSetVelParams, std::move(d), dest, addr::kHost);
}
Message reqVelParams(std::uint8_t dest, std::uint8_t channel) {
  return shortMsg(id::kMotReqVelParams, channel, 0, dest, addr::kHost);
}
namespace {
std::vector<std::uint8_t> jogData(const JogParams& p) {
  std::vector<std::uint8_t> d;
  put16(d, p.channel);
  put16(d, static_cast<std::uint16_t>(p.mode));
  putS32(d, p.step_size);
  putS32(d, p.min_velocity);
  putS32(d, p.acceleration);
  putS32(d, p.max_velocity);
  put16(d, static_cast<std::uint16_t>(p.stop_mode));
  return d;
}
}  // namespace
Message setJogParams(std::uint8_t dest, const JogParams& p) {
  return longMsg(id::kMotSetJogParams, jogData(p), dest, addr::kHost);
}
Message reqJogParams(std::uint8_t dest, std::uint8_t channel) {
  return shortMsg(id::kMotReqJogParams, channel, 0, dest, addr::kHost);
}

namespace {
std::vector<std::uint8_t> homeData(const HomeParams& p) {
  std::vector<std::uint8_t> d;
  put16(d, p.channel);
  put16(d, p.direction);
  put16(d, p.limit_switch);
  putS32(d, p.velocity);
  putS32(d, p.offset);
  return d;
}
std::vector<std::uint8_t> limSwitchData(const LimitSwitchParams& p) {
  std::vector<std::uint8_t> d;
  put16(d, p.channel);
  put16(d, p.cw_hard);
  put16(d, p.ccw_hard);
  put32(d, p.cw_soft);
  put32(d, p.ccw_soft);
  put16(d, p.soft_mode);
  return d;
}
std::vector<std::uint8_t> channelLong(std::uint16_t channel, std::int32_t value) {
  std::vector<std::uint8_t> d;
  put16(d, channel);
  putS32(d, value);
  return d;
}
}  // namespace
Message setHomeParams(std::uint8_t dest, const HomeParams& p) {
  return longMsg(id::kMotSetHomeParams, homeData(p), dest, addr::kHost);
}
Message reqHomeParams(std::uint8_t dest, std::uint8_t channel) {
  return shortMsg(id::kMotReqHomeParams, channel, 0, dest, addr::kHost);
}
Message setLimSwitchParams(std::uint8_t dest, const LimitSwitchParams& p) {
  return longMsg(id::kMotSetLimSwitchParams, limSwitchData(p), dest, addr::kHost);
}
Message reqLimSwitchParams(std::uint8_t dest, std::uint8_t channel) {
  return shortMsg(id::kMotReqLimSwitchParams, channel, 0, dest, addr::kHost);
}
Message setMoveAbsParams(std::uint8_t dest, std::uint16_t channel, std::int32_t position_counts) {
  return longMsg(id::kMotSetMoveAbsParams, channelLong(channel, position_counts), dest, addr::kHost);
}
Message setMoveRelParams(std::uint8_t dest, std::uint16_t channel, std::int32_t distance_counts) {
  return longMsg(id::kMotSetMoveRelParams, channelLong(channel, distance_counts), dest, addr::kHost);
}
Message moveAbsoluteStored(std::uint8_t dest, std::uint8_t channel) {
  return shortMsg(id::kMotMoveAbsolute, channel, 0, dest, addr::kHost);
}
Message moveRelativeStored(std::uint8_t dest, std::uint8_t channel) {
  return shortMsg(id::kMotMoveRelative, channel, 0, dest, addr::kHost);
}

// ---- Controller -> host ------------------------------------------------------------------------
Message getHwInfo(std::uint8_t source, const HwInfo& info) {
  std::vector<std::uint8_t> d;
  put32(d, info.serial);
  putText(d, info.model, 8);
  put16(d, info.hw_type);
  d.push_back(info.fw_minor);
  d.push_back(info.fw_interim);
  d.push_back(info.fw_major);
  d.push_back(0);
  putText(d, info.notes, 48);
  putText(d, "", 12);  // empty space
  put16(d, info.hw_version);
  put16(d, info.mod_state);
  put16(d, info.channels);
  return longMsg(id::kHwGetInfo, std::move(d), addr::kHost, source);
}
Message getChanEnableState(std::uint8_t source, std::uint8_t channel, bool enabled) {
  return shortMsg(id::kModGetChanEnableState, channel, enabled ? 0x01 : 0x02, addr::kHost, source);
}
Message moveHomed(std::uint8_t source, std::uint8_t channel) {
  return shortMsg(id::kMotMoveHomed, channel, 0, addr::kHost, source);
}
Message moveCompleted(std::uint8_t source, const ChannelStatus& s) {
  return longMsg(id::kMotMoveCompleted, statusData(s, false), addr::kHost, source);
}
Message moveStopped(std::uint8_t source, const ChannelStatus& s) {
  return longMsg(id::kMotMoveStopped, statusData(s, false), addr::kHost, source);
}
Message getDcStatusUpdate(std::uint8_t source, const ChannelStatus& s) {
  return longMsg(id::kMotGetDcStatusUpdate, statusData(s, false), addr::kHost, source);
}
Message getStatusUpdate(std::uint8_t source, const ChannelStatus& s) {
  return longMsg(id::kMotGetStatusUpdate, statusData(s, true), addr::kHost, source);
}
Message getVelParams(std::uint8_t source, const VelParams& p) {
  Message m = setVelParams(addr::kHost, p);
  m.id = id::kMotGetVelParams;
  m.source = source;
  return m;
}
Message getJogParams(std::uint8_t source, const JogParams& p) {
  return longMsg(id::kMotGetJogParams, jogData(p), addr::kHost, source);
}

Message getHomeParams(std::uint8_t source, const HomeParams& p) {
  return longMsg(id::kMotGetHomeParams, homeData(p), addr::kHost, source);
}
Message getLimSwitchParams(std::uint8_t source, const LimitSwitchParams& p) {
  return longMsg(id::kMotGetLimSwitchParams, limSwitchData(p), addr::kHost, source);
}
Message hwResponse(std::uint8_t source, std::uint16_t code) {
  return shortMsg(id::kHwResponse, static_cast<std::uint8_t>(code & 0xFF), static_cast<std::uint8_t>(code >> 8),
                  addr::kHost, source);
}
Message hwRichResponse(std::uint8_t source, const ControllerResponse& r) {
  std::vector<std::uint8_t> d;
  put16(d, r.message_id);
  put16(d, r.code);
  putText(d, r.text, 64);
  return longMsg(id::kHwRichResponse, std::move(d), addr::kHost, source);
}

// ---- Parsers ------------------------------------------------------------------------------------
std::optional<HwInfo> parseHwInfo(const Message& m) {
  if (m.id != id::kHwGetInfo || m.data.size() != 84) return std::nullopt;
  HwInfo h;
  h.serial = get32(m.data, 0);
  h.model = getText(m.data, 4, 8);
  h.hw_type = get16(m.data, 12);
  h.fw_minor = m.data[14];
  h.fw_interim = m.data[15];
  h.fw_major = m.data[16];
  h.notes = getText(m.data, 18, 48);
  h.hw_version = get16(m.data, 78);
  h.mod_state = get16(m.data, 80);
  h.channels = get16(m.data, 82);
  return h;
}

std::optional<ChannelStatus> parseChannelStatus(const Message& m) {
  if (m.data.size() != 14) return std::nullopt;
  ChannelStatus s;
  s.channel = get16(m.data, 0);
  s.position = getS32(m.data, 2);
  if (m.id == id::kMotGetStatusUpdate) {
    s.velocity_or_encoder = getS32(m.data, 6);
  } else if (m.id == id::kMotGetDcStatusUpdate || m.id == id::kMotMoveCompleted || m.id == id::kMotMoveStopped ||
             m.id == id::kMotMoveHomed) {
    s.velocity_or_encoder = static_cast<std::int16_t>(get16(m.data, 6));
  } else {
    return std::nullopt;
  }
  s.bits = get32(m.data, 10);
  return s;
}

std::optional<VelParams> parseVelParams(const Message& m) {
  if ((m.id != id::kMotGetVelParams && m.id != id::kMotSetVelParams) || m.data.size() != 14) return std::nullopt;
  return VelParams{get16(m.data, 0), getS32(m.data, 2), getS32(m.data, 6), getS32(m.data, 10)};
}

std::optional<JogParams> parseJogParams(const Message& m) {
  if ((m.id != id::kMotGetJogParams && m.id != id::kMotSetJogParams) || m.data.size() != 22) return std::nullopt;
  JogParams p;
  p.channel = get16(m.data, 0);
  p.mode = get16(m.data, 2) == 0x01 ? JogMode::Continuous : JogMode::SingleStep;
  p.step_size = getS32(m.data, 4);
  p.min_velocity = getS32(m.data, 8);
  p.acceleration = getS32(m.data, 12);
  p.max_velocity = getS32(m.data, 16);
  p.stop_mode = get16(m.data, 20) == 0x01 ? StopMode::Immediate : StopMode::Profiled;
  return p;
}

std::optional<HomeParams> parseHomeParams(const Message& m) {
  if ((m.id != id::kMotGetHomeParams && m.id != id::kMotSetHomeParams) || m.data.size() != 14) return std::nullopt;
  return HomeParams{get16(m.data, 0), get16(m.data, 2), get16(m.data, 4), getS32(m.data, 6), getS32(m.data, 10)};
}

std::optional<LimitSwitchParams> parseLimSwitchParams(const Message& m) {
  if ((m.id != id::kMotGetLimSwitchParams && m.id != id::kMotSetLimSwitchParams) || m.data.size() != 16)
    return std::nullopt;
  return LimitSwitchParams{get16(m.data, 0), get16(m.data, 2),  get16(m.data, 4),
                           get32(m.data, 6), get32(m.data, 10), get16(m.data, 14)};
}

std::optional<ControllerResponse> parseControllerResponse(const Message& m) {
  if (m.id == id::kHwResponse && m.data.empty())
    return ControllerResponse{0, static_cast<std::uint16_t>(m.param1 | (m.param2 << 8)), "", false};
  if (m.id == id::kHwRichResponse && m.data.size() == 68)
    return ControllerResponse{get16(m.data, 0), get16(m.data, 2), getText(m.data, 4, 64), true};
  return std::nullopt;
}

std::string describe(const ControllerResponse& r) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", r.code);
  std::string s = std::string("code ") + code + " (" + std::to_string(r.code) + ")";
  if (r.message_id) s += " after " + messageName(r.message_id);
  // The controller's text, printable characters only (it comes off the wire).
  std::string text;
  for (char c : r.text)
    if (c >= 0x20 && c < 0x7F) text.push_back(c);
  while (!text.empty() && text.back() == ' ') text.pop_back();
  s += text.empty() ? std::string(r.rich ? ": (no text)" : ": HW_RESPONSE, no text") : ": " + text;
  return s;
}

std::optional<ChannelValue> parseMoveParams(const Message& m) {
  const bool params = m.id == id::kMotSetMoveAbsParams || m.id == id::kMotGetMoveAbsParams ||
                      m.id == id::kMotSetMoveRelParams || m.id == id::kMotGetMoveRelParams;
  if (!params || m.data.size() != 6) return std::nullopt;
  return ChannelValue{get16(m.data, 0), getS32(m.data, 2)};
}

bool isStoredMove(const Message& m) {
  return (m.id == id::kMotMoveAbsolute || m.id == id::kMotMoveRelative) && m.data.empty();
}

std::optional<ChannelValue> parseMoveAbsolute(const Message& m) {
  return parseChannelLong(m, id::kMotMoveAbsolute);
}
std::optional<ChannelValue> parseMoveRelative(const Message& m) {
  return parseChannelLong(m, id::kMotMoveRelative);
}

}  // namespace fovea::apt
