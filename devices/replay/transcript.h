#pragma once
// APT transcripts: what passed on one link, with time, so that a recording made on real
// hardware can be replayed as a regression test (ReplayTransport).
//
// Format (text, one entry a line): the `fovea-cli stage --trace` line with the link-clock
// time in seconds in front,
//
//   0.000000 TX 05 00 00 00 50 01
//   0.003100 RX 06 00 54 00 81 50 ...
//   2.500000 UNPLUG
//
// TX: bytes the host sent; RX: bytes the controller sent (FTDI status bytes removed);
// UNPLUG: the link vanished. Times never decrease. Blank lines and lines starting with '#'
// are comments.
#include <cstdint>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "devices/stage/apt_log.h"

namespace fovea::devices {

struct TranscriptEntry {
  enum class Kind { Tx, Rx, Unplug };
  double t_s = 0;
  Kind kind = Kind::Tx;
  std::vector<std::uint8_t> bytes;
  int line = 0;  // 1-based line in the transcript text
};

// Throws std::invalid_argument "NAME:LINE: ..." naming the first malformed line.
std::vector<TranscriptEntry> parseTranscript(const std::string& text, const std::string& name = "transcript");
// The largest transcript file read (a recorded session of hours is a few MB).
inline constexpr std::size_t kMaxTranscriptBytes = 16u << 20;
std::vector<TranscriptEntry> readTranscriptFile(const std::string& path);  // also throws for an unreadable file
std::string transcriptLine(double t_s, bool transmitted, std::span<const std::uint8_t> raw);

// A AptLogSink that writes transcript lines, stamped by the link's clock.
class TranscriptRecorder : public AptLogSink {
 public:
  // Throws std::runtime_error naming the path.
  TranscriptRecorder(const std::string& path, std::function<double()> clock);
  void message(bool transmitted, std::span<const std::uint8_t> raw) override;

 private:
  std::mutex mutex_;
  std::ofstream out_;
  std::function<double()> clock_;
  double t0_ = 0;  // times are written relative to the recorder's start
};

// Several sinks at once (a --trace file and a transcript).
class TraceFanout : public AptLogSink {
 public:
  explicit TraceFanout(std::vector<std::shared_ptr<AptLogSink>> sinks) : sinks_(std::move(sinks)) {}
  void message(bool transmitted, std::span<const std::uint8_t> raw) override {
    for (auto& s : sinks_) s->message(transmitted, raw);
  }

 private:
  std::vector<std::shared_ptr<AptLogSink>> sinks_;
};

}  // namespace fovea::devices
