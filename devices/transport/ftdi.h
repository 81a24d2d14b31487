#pragma once
// FTDI USB-serial details of Thorlabs cubes (FT232-family bridge, VID 0x0403, PID 0xFAF0),
// as pure functions: the vendor control requests, the baud-rate divisor encoding and the
// two modem-status bytes the chip puts at the start of every IN packet.
// Sources: FTDI AN232B-05 "Configuring FT232R, FT2232 and FT232B baud rates"; Linux
// drivers/usb/serial/ftdi_sio.h (request numbers and values); Thorlabs APT protocol
// document, "USB device initialisation" (115200 8N1, purge, reset, RTS/CTS, RTS set).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace fovea::devices::ftdi {

inline constexpr std::uint16_t kThorlabsVid = 0x0403;
inline constexpr std::uint16_t kThorlabsPid = 0xFAF0;
inline constexpr std::uint8_t kEndpointIn = 0x81;
inline constexpr std::uint8_t kEndpointOut = 0x02;
inline constexpr std::size_t kFullSpeedPacket = 64;

// bmRequestType 0x40: vendor request, host to device, recipient device.
inline constexpr std::uint8_t kRequestTypeOut = 0x40;
inline constexpr std::uint8_t kReset = 0;  // wValue 0 reset, 1 purge RX, 2 purge TX
inline constexpr std::uint16_t kResetSio = 0, kPurgeRx = 1, kPurgeTx = 2;
inline constexpr std::uint8_t kSetModemCtrl = 1;  // wValue: mask in the high byte, level in the low byte
inline constexpr std::uint16_t kRtsHigh = 0x0202;
inline constexpr std::uint8_t kSetFlowCtrl = 2;  // wIndex high byte: 0x01 RTS/CTS
inline constexpr std::uint16_t kFlowRtsCts = 0x0100;
inline constexpr std::uint8_t kSetBaudRate = 3;
inline constexpr std::uint8_t kSetData = 4;  // wValue: data bits | parity << 8 | stop bits << 11
inline constexpr std::uint16_t kData8N1 = 0x0008;
inline constexpr std::uint8_t kSetLatencyTimer = 9;
inline constexpr std::uint16_t kInterfaceA = 1;  // wIndex of the (single) port

struct BaudDivisor {
  std::uint16_t value = 0;  // wValue of SET_BAUDRATE
  std::uint16_t index = 0;  // wIndex (divisor bit 16 for FT232B/R)
  double actual_baud = 0;
};
// FT232B/R: 3 MHz reference, divisor n + k/8 (k in eighths, encoded with the sub-integer
// code table {0,3,2,4,1,5,6,7} in bits 14..16); divisors 1 and 1.5 are special (0 and 1).
BaudDivisor baudDivisor(int baud);

// Removes the two status bytes at the start of each max-packet chunk of a bulk IN transfer.
std::vector<std::uint8_t> stripStatusBytes(std::span<const std::uint8_t> transfer, std::size_t max_packet);

}  // namespace fovea::devices::ftdi
