#include "devices/apt/apt_decoder.h"

namespace fovea::apt {

void StreamDecoder::feed(std::span<const std::uint8_t> bytes) {
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

void StreamDecoder::reset() {
  buffer_.clear();
  in_sync_ = false;
}

std::optional<Message> StreamDecoder::next() {
  while (buffer_.size() >= 6) {
    const std::uint16_t msg_id = static_cast<std::uint16_t>(buffer_[0] | (buffer_[1] << 8));
    const std::uint8_t dest_raw = buffer_[4];
    const std::uint8_t source = buffer_[5];
    const bool has_data = (dest_raw & addr::kDataFlag) != 0;
    const std::uint8_t dest = static_cast<std::uint8_t>(dest_raw & ~addr::kDataFlag);
    const std::uint16_t length = has_data ? static_cast<std::uint16_t>(buffer_[2] | (buffer_[3] << 8)) : 0;

    // Every message on a host link has the host at one end (rack-internal traffic between
    // bays never reaches USB), which rejects most random address pairs.
    bool valid = addr::plausible(dest) && addr::plausible(source) && dest != source &&
                 (dest == addr::kHost || source == addr::kHost);
    if (valid) {
      if (in_sync_ && !knownDataLength(msg_id)) {
        // An id this codec does not know: only inside the documented id blocks (generic
        // 0x00xx/0x02xx, motor 0x04xx-0x05xx, piezo/other 0x06xx-0x08xx) and short.
        const unsigned block = msg_id >> 8;
        const bool documented_block = block == 0x00 || block == 0x02 || (block >= 0x04 && block <= 0x08);
        valid = documented_block && (!has_data || (length > 0 && length <= kMaxUnknownLength));
      } else {
        valid = acceptsLength(msg_id, length) && (has_data == (length > 0));
      }
    }
    if (!valid) {
      buffer_.pop_front();
      ++discarded_;
      in_sync_ = false;
      continue;
    }
    const std::size_t total = 6u + length;
    if (buffer_.size() < total) return std::nullopt;  // partial: wait for the rest

    Message m;
    m.id = msg_id;
    m.dest = dest;
    m.source = source;
    if (!has_data) {
      m.param1 = buffer_[2];
      m.param2 = buffer_[3];
    } else {
      m.data.assign(buffer_.begin() + 6, buffer_.begin() + static_cast<std::ptrdiff_t>(total));
    }
    last_raw_.assign(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(total));
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(total));
    in_sync_ = true;
    return m;
  }
  return std::nullopt;
}

}  // namespace fovea::apt
