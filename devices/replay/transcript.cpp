#include "devices/replay/transcript.h"

#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "devices/apt/apt_message.h"
#include "model/io/json_input.h"

namespace fovea::devices {

namespace {
int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}
}  // namespace

std::vector<TranscriptEntry> parseTranscript(const std::string& text, const std::string& name) {
  std::vector<TranscriptEntry> out;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  double last_t = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    auto fail = [&](const std::string& why) {
      throw std::invalid_argument(name + ":" + std::to_string(number) + ": " + why);
    };
    std::istringstream fields(line);
    std::string time, kind;
    fields >> time >> kind;
    TranscriptEntry e;
    e.line = number;
    std::size_t used = 0;
    try {
      e.t_s = std::stod(time, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != time.size() || !(e.t_s >= 0) || e.t_s > 1e9)
      fail("expected a time in seconds (0 .. 1e9) first, got '" + time + "'");
    if (e.t_s < last_t) fail("time " + time + " s runs backwards");
    last_t = e.t_s;
    if (kind == "TX")
      e.kind = TranscriptEntry::Kind::Tx;
    else if (kind == "RX")
      e.kind = TranscriptEntry::Kind::Rx;
    else if (kind == "UNPLUG")
      e.kind = TranscriptEntry::Kind::Unplug;
    else
      fail("expected TX, RX or UNPLUG after the time, got '" + kind + "'");
    std::string pair;
    while (fields >> pair) {
      if (e.kind == TranscriptEntry::Kind::Unplug) fail("UNPLUG takes no bytes");
      if (pair.size() != 2 || hexDigit(pair[0]) < 0 || hexDigit(pair[1]) < 0)
        fail("expected hex byte pairs (\"0A 1B\"), got '" + pair + "'");
      e.bytes.push_back(static_cast<std::uint8_t>(hexDigit(pair[0]) * 16 + hexDigit(pair[1])));
    }
    if (e.kind != TranscriptEntry::Kind::Unplug && e.bytes.empty()) fail(kind + " without bytes");
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<TranscriptEntry> readTranscriptFile(const std::string& path) {
  // A regular file of bounded size (a FIFO, a device or /dev/zero is refused, not read forever).
  auto text = readInputFile(path, kMaxTranscriptBytes);
  if (text.index() == 1) throw std::invalid_argument("cannot read the transcript '" + path + "': " + std::get<1>(text));
  return parseTranscript(std::get<0>(text), path);
}

std::string transcriptLine(double t_s, bool transmitted, std::span<const std::uint8_t> raw) {
  char stamp[32];
  std::snprintf(stamp, sizeof stamp, "%.6f ", t_s);
  return stamp + aptLogLine(transmitted, raw);
}

TranscriptRecorder::TranscriptRecorder(const std::string& path, std::function<double()> clock)
    : out_(path, std::ios::out | std::ios::trunc), clock_(std::move(clock)), t0_(clock_ ? clock_() : 0.0) {
  if (!out_) throw std::runtime_error("cannot write the transcript file '" + path + "'");
  out_ << "# fovea APT transcript: seconds since the link opened, TX/RX bytes (see devices/replay/transcript.h)\n";
}

void TranscriptRecorder::message(bool transmitted, std::span<const std::uint8_t> raw) {
  std::lock_guard lock(mutex_);
  out_ << transcriptLine(clock_ ? clock_() - t0_ : 0.0, transmitted, raw) << '\n';
  out_.flush();
}

}  // namespace fovea::devices
