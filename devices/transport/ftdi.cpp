#include "devices/transport/ftdi.h"

#include <algorithm>
#include <cmath>

namespace fovea::devices::ftdi {

BaudDivisor baudDivisor(int baud) {
  constexpr double kReference = 3e6;  // 48 MHz / 16
  BaudDivisor out;
  if (baud <= 0) return out;
  if (baud >= 3000000) {
    out.value = 0;  // divisor 1
    out.actual_baud = kReference;
    return out;
  }
  if (baud >= 2000000) {
    out.value = 1;  // divisor 1.5
    out.actual_baud = 2e6;
    return out;
  }
  // Divisor in eighths, rounded to nearest; the chip supports 2 .. 16383.875.
  long eighths = std::lround(kReference * 8.0 / baud);
  eighths = std::clamp(eighths, 16L, 0x1FFFFL);
  static constexpr std::uint32_t kSubInteger[8] = {0, 3, 2, 4, 1, 5, 6, 7};
  const std::uint32_t encoded = static_cast<std::uint32_t>(eighths >> 3) | (kSubInteger[eighths & 7] << 14);
  out.value = static_cast<std::uint16_t>(encoded & 0xFFFF);
  out.index = static_cast<std::uint16_t>(encoded >> 16);
  out.actual_baud = kReference * 8.0 / static_cast<double>(eighths);
  return out;
}

std::vector<std::uint8_t> stripStatusBytes(std::span<const std::uint8_t> transfer, std::size_t max_packet) {
  std::vector<std::uint8_t> out;
  if (max_packet <= 2) return out;
  out.reserve(transfer.size());
  for (std::size_t at = 0; at < transfer.size(); at += max_packet) {
    const std::size_t end = std::min(transfer.size(), at + max_packet);
    if (end - at > 2)
      out.insert(out.end(), transfer.begin() + static_cast<std::ptrdiff_t>(at + 2),
                 transfer.begin() + static_cast<std::ptrdiff_t>(end));
  }
  return out;
}

}  // namespace fovea::devices::ftdi
