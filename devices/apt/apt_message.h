#pragma once
// Thorlabs APT host–controller protocol: messages as plain structs and their exact bytes.
// A pure codec: no I/O. Source: "Thorlabs APT Controllers Host-Controller Communications
// Protocol" (its revisions 15–37 agree on everything used here), section "Message structure":
//
//   header-only message (6 bytes):  id_lo id_hi param1 param2 dest        source
//   message with data (6 + N):      id_lo id_hi len_lo len_hi dest|0x80   source  data[N]
//
// The message id and every multi-byte field are little-endian. Addresses: 0x01 host, 0x50
// generic USB unit (single-channel cubes: KDC101, TDC001, KBD101, K10CR1), 0x11 rack
// controller, 0x21.. bays 0.. of a rack. "Chan Ident" is 1 for channel 1 (word in data
// packets, byte in param1).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace fovea::apt {

namespace addr {
inline constexpr std::uint8_t kHost = 0x01;
inline constexpr std::uint8_t kRack = 0x11;
inline constexpr std::uint8_t kBay0 = 0x21;  // bays 0x21 .. 0x2A
inline constexpr std::uint8_t kGenericUsb = 0x50;
inline constexpr std::uint8_t kDataFlag = 0x80;  // OR-ed into dest when a data packet follows
bool plausible(std::uint8_t address);            // one of the addresses above (no data flag)
}  // namespace addr

// Message ids (protocol document, "Generic System Control Messages" and "Motor Control Messages").
namespace id {
inline constexpr std::uint16_t kHwDisconnect = 0x0002;
inline constexpr std::uint16_t kHwReqInfo = 0x0005;
inline constexpr std::uint16_t kHwGetInfo = 0x0006;
inline constexpr std::uint16_t kHwStartUpdateMsgs = 0x0011;
inline constexpr std::uint16_t kHwStopUpdateMsgs = 0x0012;
inline constexpr std::uint16_t kHwResponse = 0x0080;
inline constexpr std::uint16_t kHwRichResponse = 0x0081;
inline constexpr std::uint16_t kModSetChanEnableState = 0x0210;
inline constexpr std::uint16_t kModReqChanEnableState = 0x0211;
inline constexpr std::uint16_t kModGetChanEnableState = 0x0212;
inline constexpr std::uint16_t kModIdentify = 0x0223;
inline constexpr std::uint16_t kMotSetVelParams = 0x0413;
inline constexpr std::uint16_t kMotSetLimSwitchParams = 0x0423;
inline constexpr std::uint16_t kMotReqLimSwitchParams = 0x0424;
inline constexpr std::uint16_t kMotGetLimSwitchParams = 0x0425;
inline constexpr std::uint16_t kMotSetHomeParams = 0x0440;
inline constexpr std::uint16_t kMotReqHomeParams = 0x0441;
inline constexpr std::uint16_t kMotGetHomeParams = 0x0442;
inline constexpr std::uint16_t kMotSetMoveRelParams = 0x0445;  // distance of the header-only MOVE_RELATIVE
inline constexpr std::uint16_t kMotReqMoveRelParams = 0x0446;
inline constexpr std::uint16_t kMotGetMoveRelParams = 0x0447;
inline constexpr std::uint16_t kMotSetMoveAbsParams = 0x0450;  // target of the header-only MOVE_ABSOLUTE
inline constexpr std::uint16_t kMotReqMoveAbsParams = 0x0451;
inline constexpr std::uint16_t kMotGetMoveAbsParams = 0x0452;
inline constexpr std::uint16_t kMotReqVelParams = 0x0414;
inline constexpr std::uint16_t kMotGetVelParams = 0x0415;
inline constexpr std::uint16_t kMotSetJogParams = 0x0416;
inline constexpr std::uint16_t kMotReqJogParams = 0x0417;
inline constexpr std::uint16_t kMotGetJogParams = 0x0418;
inline constexpr std::uint16_t kMotMoveHome = 0x0443;
inline constexpr std::uint16_t kMotMoveHomed = 0x0444;
inline constexpr std::uint16_t kMotMoveRelative = 0x0448;
inline constexpr std::uint16_t kMotMoveAbsolute = 0x0453;
inline constexpr std::uint16_t kMotMoveCompleted = 0x0464;
inline constexpr std::uint16_t kMotMoveStop = 0x0465;
inline constexpr std::uint16_t kMotMoveStopped = 0x0466;
inline constexpr std::uint16_t kMotMoveJog = 0x046A;
inline constexpr std::uint16_t kMotReqStatusUpdate = 0x0480;  // stepper controllers (K10CR1)
inline constexpr std::uint16_t kMotGetStatusUpdate = 0x0481;
inline constexpr std::uint16_t kMotReqDcStatusUpdate = 0x0490;  // DC servo / brushless (KDC101, TDC001, KBD101)
inline constexpr std::uint16_t kMotGetDcStatusUpdate = 0x0491;
inline constexpr std::uint16_t kMotAckDcStatusUpdate = 0x0492;  // host keep-alive while update messages run
}  // namespace id

// Expected data length of a known message id: 0 for header-only messages, N for messages
// with an N-byte data packet, nullopt for an id this codec does not know. Some ids have two
// valid forms, both accepted (see acceptsLength): MOVE_COMPLETED, MOVE_STOPPED and
// MOVE_HOMED are header-only on old controllers and carry a 14-byte status on newer ones;
// MOVE_ABSOLUTE and MOVE_RELATIVE have a header-only form (channel in param1) that moves by
// the MOVEABSPARAMS / MOVERELPARAMS set before, besides the 6-byte form with the counts.
std::optional<std::uint16_t> knownDataLength(std::uint16_t message_id);
bool acceptsLength(std::uint16_t message_id, std::uint16_t data_length);
std::string messageName(std::uint16_t message_id);  // "MOT_MOVE_ABSOLUTE", or "0x1234"

// Channel ident of channel 1..4. Single- and dual-channel controllers number channels
// 1, 2, 3, 4; controllers that address channels as bits (protocol document, "Chan Ident":
// 0x01, 0x02, 0x04, 0x08) need the bit mask for channels 3 and 4.
std::uint8_t channelIdent(int channel, bool bit_mask);

struct Message {
  std::uint16_t id = 0;
  std::uint8_t param1 = 0, param2 = 0;  // header-only messages
  std::uint8_t dest = addr::kGenericUsb;
  std::uint8_t source = addr::kHost;
  std::vector<std::uint8_t> data;  // non-empty: long form (length in header, dest|0x80)
  bool operator==(const Message&) const = default;
};

std::vector<std::uint8_t> encode(const Message& m);
// Upper-case hex pairs separated by single spaces: "23 02 00 00 50 01".
std::string toHex(std::span<const std::uint8_t> bytes);

// ---- Enumerations of the parameter bytes -------------------------------------------------
enum class JogDirection : std::uint8_t { Forward = 0x01, Reverse = 0x02 };
enum class StopMode : std::uint8_t { Immediate = 0x01, Profiled = 0x02 };
enum class JogMode : std::uint16_t { Continuous = 0x01, SingleStep = 0x02 };

// Status bits of DCSTATUSUPDATE / STATUSUPDATE / MOVE_COMPLETED (protocol document,
// MGMSG_MOT_GET_DCSTATUSUPDATE "StatusBits").
namespace status {
inline constexpr std::uint32_t kForwardHardLimit = 0x00000001;  // CW hardware limit switch
inline constexpr std::uint32_t kReverseHardLimit = 0x00000002;  // CCW hardware limit switch
inline constexpr std::uint32_t kMovingForward = 0x00000010;
inline constexpr std::uint32_t kMovingReverse = 0x00000020;
inline constexpr std::uint32_t kJoggingForward = 0x00000040;
inline constexpr std::uint32_t kJoggingReverse = 0x00000080;
inline constexpr std::uint32_t kMotorConnected = 0x00000100;
inline constexpr std::uint32_t kHoming = 0x00000200;
inline constexpr std::uint32_t kHomed = 0x00000400;
inline constexpr std::uint32_t kTracking = 0x00001000;
inline constexpr std::uint32_t kSettled = 0x00002000;
inline constexpr std::uint32_t kMotionError = 0x00004000;
inline constexpr std::uint32_t kCurrentLimit = 0x01000000;
inline constexpr std::uint32_t kChannelEnabled = 0x80000000;
inline constexpr std::uint32_t kMovingMask =
    kMovingForward | kMovingReverse | kJoggingForward | kJoggingReverse | kHoming;
}  // namespace status

// ---- Data packets -------------------------------------------------------------------------
struct HwInfo {  // HW_GET_INFO, 84 data bytes
  std::uint32_t serial = 0;
  std::string model;           // 8 chars, NUL padded ("KDC101")
  std::uint16_t hw_type = 44;  // document: 44 brushless DC controller, 45 multi-channel motherboard
  std::uint8_t fw_minor = 0, fw_interim = 0, fw_major = 0;
  std::string notes;  // 48 chars
  std::uint16_t hw_version = 1, mod_state = 0, channels = 1;
  bool operator==(const HwInfo&) const = default;
};

struct ChannelStatus {  // DCSTATUSUPDATE (and STATUSUPDATE), 14 data bytes
  std::uint16_t channel = 1;
  std::int32_t position = 0;             // encoder counts
  std::int32_t velocity_or_encoder = 0;  // DC: word velocity; stepper: long encoder count
  std::uint32_t bits = 0;
  bool operator==(const ChannelStatus&) const = default;
};

struct VelParams {  // SET/GET_VELPARAMS, 14 data bytes, APT units
  std::uint16_t channel = 1;
  std::int32_t min_velocity = 0, acceleration = 0, max_velocity = 0;
  bool operator==(const VelParams&) const = default;
};

struct JogParams {  // SET/GET_JOGPARAMS, 22 data bytes, APT units
  std::uint16_t channel = 1;
  JogMode mode = JogMode::SingleStep;
  std::int32_t step_size = 0;  // encoder counts
  std::int32_t min_velocity = 0, acceleration = 0, max_velocity = 0;
  StopMode stop_mode = StopMode::Profiled;
  bool operator==(const JogParams&) const = default;
};

struct HomeParams {  // SET/GET_HOMEPARAMS, 14 data bytes
  std::uint16_t channel = 1;
  std::uint16_t direction = 2;     // 1 forward, 2 reverse
  std::uint16_t limit_switch = 1;  // 1 reverse (CCW) switch, 4 forward (CW) switch
  std::int32_t velocity = 0;       // APT velocity units
  std::int32_t offset = 0;         // encoder counts
  bool operator==(const HomeParams&) const = default;
};

// Limit-switch modes of SET/GET_LIMSWITCHPARAMS (protocol document): 1 ignore, 2 switch
// makes on contact, 3 switch breaks on contact, 4/5 the same for the homing switch only;
// 0x80 OR-ed in swaps CW and CCW.
struct LimitSwitchParams {  // SET/GET_LIMSWITCHPARAMS, 16 data bytes
  std::uint16_t channel = 1;
  std::uint16_t cw_hard = 2, ccw_hard = 2;
  std::uint32_t cw_soft = 0, ccw_soft = 0;  // encoder counts (x 134218 on some controllers)
  std::uint16_t soft_mode = 1;              // 1 ignore soft limits, 2 stop immediately, 3 profiled stop
  bool operator==(const LimitSwitchParams&) const = default;
};

// A controller's error report: HW_RICHRESPONSE (id of the message that caused it, code,
// 64-character text) or HW_RESPONSE (header-only; the code in param1/param2).
struct ControllerResponse {
  std::uint16_t message_id = 0;  // the offending message (0: not given)
  std::uint16_t code = 0;
  std::string text;
  bool rich = false;
};

// ---- Host -> controller ----------------------------------------------------------------
Message identify(std::uint8_t dest = addr::kGenericUsb, std::uint8_t channel = 0);
Message reqHwInfo(std::uint8_t dest = addr::kGenericUsb);
Message setChanEnableState(std::uint8_t dest, std::uint8_t channel, bool enabled);
Message reqChanEnableState(std::uint8_t dest, std::uint8_t channel);
Message startUpdateMsgs(std::uint8_t dest);
Message stopUpdateMsgs(std::uint8_t dest);
Message moveHome(std::uint8_t dest, std::uint8_t channel);
Message moveAbsolute(std::uint8_t dest, std::uint16_t channel, std::int32_t position_counts);
Message moveRelative(std::uint8_t dest, std::uint16_t channel, std::int32_t distance_counts);
Message moveJog(std::uint8_t dest, std::uint8_t channel, JogDirection direction);
Message moveStop(std::uint8_t dest, std::uint8_t channel, StopMode mode);
Message reqDcStatusUpdate(std::uint8_t dest, std::uint8_t channel);
Message ackDcStatusUpdate(std::uint8_t dest);
Message reqStatusUpdate(std::uint8_t dest, std::uint8_t channel);
Message setVelParams(std::uint8_t dest, const VelParams& p);
Message reqVelParams(std::uint8_t dest, std::uint8_t channel);
Message setJogParams(std::uint8_t dest, const JogParams& p);
Message reqJogParams(std::uint8_t dest, std::uint8_t channel);
Message setHomeParams(std::uint8_t dest, const HomeParams& p);
Message reqHomeParams(std::uint8_t dest, std::uint8_t channel);
Message setLimSwitchParams(std::uint8_t dest, const LimitSwitchParams& p);
Message reqLimSwitchParams(std::uint8_t dest, std::uint8_t channel);
Message setMoveAbsParams(std::uint8_t dest, std::uint16_t channel, std::int32_t position_counts);
Message setMoveRelParams(std::uint8_t dest, std::uint16_t channel, std::int32_t distance_counts);
Message moveAbsoluteStored(std::uint8_t dest, std::uint8_t channel);  // header-only form
Message moveRelativeStored(std::uint8_t dest, std::uint8_t channel);  // header-only form

// ---- Controller -> host (the emulator builds these; dest is the host) ----------------------
Message getHwInfo(std::uint8_t source, const HwInfo& info);
Message getChanEnableState(std::uint8_t source, std::uint8_t channel, bool enabled);
Message moveHomed(std::uint8_t source, std::uint8_t channel);
Message moveCompleted(std::uint8_t source, const ChannelStatus& s);
Message moveStopped(std::uint8_t source, const ChannelStatus& s);
Message getDcStatusUpdate(std::uint8_t source, const ChannelStatus& s);
Message getStatusUpdate(std::uint8_t source, const ChannelStatus& s);  // stepper layout
Message getVelParams(std::uint8_t source, const VelParams& p);
Message getJogParams(std::uint8_t source, const JogParams& p);
Message getHomeParams(std::uint8_t source, const HomeParams& p);
Message getLimSwitchParams(std::uint8_t source, const LimitSwitchParams& p);
Message hwResponse(std::uint8_t source, std::uint16_t code);
Message hwRichResponse(std::uint8_t source, const ControllerResponse& r);

// ---- Parsers (nullopt: wrong id or wrong length) ---------------------------------------------
std::optional<HwInfo> parseHwInfo(const Message& m);
// DC layout (position long, velocity word, reserved word, bits) for GET_DCSTATUSUPDATE,
// MOVE_COMPLETED, MOVE_STOPPED; stepper layout (position long, encoder long, bits) for
// GET_STATUSUPDATE.
std::optional<ChannelStatus> parseChannelStatus(const Message& m);
std::optional<VelParams> parseVelParams(const Message& m);                    // GET_ or SET_VELPARAMS
std::optional<JogParams> parseJogParams(const Message& m);                    // GET_ or SET_JOGPARAMS
std::optional<HomeParams> parseHomeParams(const Message& m);                  // GET_ or SET_HOMEPARAMS
std::optional<LimitSwitchParams> parseLimSwitchParams(const Message& m);      // GET_ or SET_LIMSWITCHPARAMS
std::optional<ControllerResponse> parseControllerResponse(const Message& m);  // HW_RESPONSE / HW_RICHRESPONSE
// "code 0x0042 (after MOT_MOVE_ABSOLUTE): Move beyond travel" (the controller's words).
std::string describe(const ControllerResponse& r);
struct ChannelValue {
  std::uint16_t channel = 1;
  std::int32_t value = 0;
};
// The 6-byte forms only (the header-only forms carry no counts: see isStoredMove).
std::optional<ChannelValue> parseMoveAbsolute(const Message& m);
std::optional<ChannelValue> parseMoveRelative(const Message& m);
std::optional<ChannelValue> parseMoveParams(const Message& m);  // SET/GET_MOVEABSPARAMS, _MOVERELPARAMS
// A header-only MOVE_ABSOLUTE / MOVE_RELATIVE (moves by the stored parameters).
bool isStoredMove(const Message& m);

}  // namespace fovea::apt
