#pragma once
// A Transport that plays the controller's side of a transcript: the host's writes must be
// the transcript's TX bytes, in order (any chunking); reads return its RX bytes once the
// link clock has reached their time; UNPLUG makes the link vanish. The clock is simulated
// (starts at 0, jumps), so a recorded 10 s move replays at once.
//
// A write that differs from the transcript throws DeviceError(Protocol) naming the line and
// both byte strings, so a change in what the host sends shows up as a failed replay.
#include <deque>
#include <string>
#include <vector>

#include "devices/replay/transcript.h"
#include "devices/transport/transport.h"

namespace fovea::devices {

class ReplayTransport : public Transport {
 public:
  ReplayTransport(std::vector<TranscriptEntry> entries, DeviceInfo info, std::string name = "transcript");
  void open() override;
  void close() override { open_ = false; }
  bool isOpen() const override { return open_ && !unplugged_; }
  void write(std::span<const std::uint8_t> bytes) override;
  std::vector<std::uint8_t> read(std::chrono::milliseconds timeout) override;
  DeviceInfo info() const override { return info_; }
  double now() const override { return now_; }

  // Entries not yet played (0 when the host did everything the transcript holds).
  std::size_t remaining() const { return entries_.size() - next_; }
  // "line 12: TX 53 04 ..." of the next entry, or "end of transcript".
  std::string nextDescription() const;

 private:
  [[noreturn]] void unplug(const TranscriptEntry& e);
  std::vector<TranscriptEntry> entries_;
  DeviceInfo info_;
  std::string name_;
  std::size_t next_ = 0;
  std::size_t tx_matched_ = 0;  // bytes of entries_[next_] (a TX) already written
  std::vector<std::uint8_t> rx_ready_;
  double now_ = 0;
  bool open_ = false, unplugged_ = false;
};

}  // namespace fovea::devices
