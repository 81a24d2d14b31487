#pragma once
// Streaming APT decoder: bytes in (any chunking), whole messages out. Survives garbage,
// partial and concatenated packets and resynchronises on the next valid header.
//
// Every valid header form is accepted, including the header-only MOVE_ABSOLUTE (0x0453) /
// MOVE_RELATIVE (0x0448) and the header-only or 14-byte completions.
// Header validation (both directions): addresses plausible, distinct, one of them the host. While in sync (the previous
// message ended exactly here) a header with an unknown id is accepted when its addresses are plausible, its id lies in
// a documented id block and its length is short, so messages this codec does not know still pass through. After garbage
// (out of sync) only known message ids with their documented data length and plausible addresses are accepted, so
// random bytes almost never fake a header (~40 ids of 65536, x the address checks).
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "devices/apt/apt_message.h"

namespace fovea::apt {

class StreamDecoder {
 public:
  void feed(std::span<const std::uint8_t> bytes);
  // The next complete message, or nullopt when more bytes are needed.
  std::optional<Message> next();
  // Raw bytes of the last message next() returned (for traces).
  const std::vector<std::uint8_t>& lastRaw() const { return last_raw_; }
  std::size_t discardedBytes() const { return discarded_; }
  std::size_t buffered() const { return buffer_.size(); }
  void reset();

  static constexpr std::uint16_t kMaxDataLength = 512;     // upper bound of any buffered message
  static constexpr std::uint16_t kMaxUnknownLength = 128;  // unknown ids: longer is taken as noise

 private:
  std::deque<std::uint8_t> buffer_;
  std::vector<std::uint8_t> last_raw_;
  std::size_t discarded_ = 0;
  bool in_sync_ = false;  // a stream's first bytes may be leftovers: start strict
};

}  // namespace fovea::apt
