#include "devices/replay/replay_transport.h"

#include <algorithm>
#include <utility>

#include "devices/apt/apt_message.h"
#include "devices/transport/device_error.h"

namespace fovea::devices {

using Kind = TranscriptEntry::Kind;

ReplayTransport::ReplayTransport(std::vector<TranscriptEntry> entries, DeviceInfo info, std::string name)
    : entries_(std::move(entries)), info_(std::move(info)), name_(std::move(name)) {}

void ReplayTransport::open() {
  if (unplugged_) throw DeviceError(DeviceError::Kind::NotFound, name_ + ": the replayed controller was unplugged");
  open_ = true;
  notifyEvent(TransportEvent::Connected);
}

std::string ReplayTransport::nextDescription() const {
  if (next_ >= entries_.size()) return "end of transcript";
  const auto& e = entries_[next_];
  const char* kind = e.kind == Kind::Tx ? "TX" : e.kind == Kind::Rx ? "RX" : "UNPLUG";
  return "line " + std::to_string(e.line) + ": " + kind + (e.bytes.empty() ? "" : " " + apt::toHex(e.bytes));
}

void ReplayTransport::unplug(const TranscriptEntry& e) {
  now_ = std::max(now_, e.t_s);
  unplugged_ = true;
  ++next_;
  notifyEvent(TransportEvent::Disconnected);
  throw DeviceError(DeviceError::Kind::Disconnected, name_ + ": controller " + info_.serial + " is disconnected");
}

void ReplayTransport::write(std::span<const std::uint8_t> bytes) {
  if (!isOpen()) throw DeviceError(DeviceError::Kind::Disconnected, name_ + ": the link is not open");
  std::size_t at = 0;
  while (at < bytes.size()) {
    // Controller bytes recorded before this TX had arrived already: make them readable.
    while (next_ < entries_.size() && entries_[next_].kind == Kind::Rx && tx_matched_ == 0) {
      now_ = std::max(now_, entries_[next_].t_s);
      rx_ready_.insert(rx_ready_.end(), entries_[next_].bytes.begin(), entries_[next_].bytes.end());
      ++next_;
    }
    if (next_ < entries_.size() && entries_[next_].kind == Kind::Unplug) unplug(entries_[next_]);
    if (next_ >= entries_.size())
      throw DeviceError(DeviceError::Kind::Protocol, name_ + ": the host sent " + apt::toHex(bytes.subspan(at)) +
                                                         " after the end of the transcript");
    const TranscriptEntry& e = entries_[next_];
    const std::size_t n = std::min(bytes.size() - at, e.bytes.size() - tx_matched_);
    if (!std::equal(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                    bytes.begin() + static_cast<std::ptrdiff_t>(at + n),
                    e.bytes.begin() + static_cast<std::ptrdiff_t>(tx_matched_)))
      throw DeviceError(DeviceError::Kind::Protocol, name_ + ":" + std::to_string(e.line) + ": the host sent " +
                                                         apt::toHex(bytes) + ", the transcript expects TX " +
                                                         apt::toHex(e.bytes));
    now_ = std::max(now_, e.t_s);
    at += n;
    tx_matched_ += n;
    if (tx_matched_ == e.bytes.size()) {
      tx_matched_ = 0;
      ++next_;
    }
  }
}

std::vector<std::uint8_t> ReplayTransport::read(std::chrono::milliseconds timeout) {
  if (!isOpen()) throw DeviceError(DeviceError::Kind::Disconnected, name_ + ": the link is not open");
  if (!rx_ready_.empty()) return std::exchange(rx_ready_, {});
  const double deadline = now_ + std::chrono::duration<double>(timeout).count();
  if (next_ < entries_.size() && tx_matched_ == 0 && entries_[next_].t_s <= deadline) {
    const TranscriptEntry& e = entries_[next_];
    if (e.kind == Kind::Unplug) unplug(e);
    if (e.kind == Kind::Rx) {
      now_ = std::max(now_, e.t_s);
      ++next_;
      return e.bytes;
    }
  }
  now_ = deadline;  // nothing due (or the transcript waits for the host): the timeout passes
  return {};
}

}  // namespace fovea::devices
