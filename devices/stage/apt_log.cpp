#include "devices/stage/apt_log.h"

#include <stdexcept>

#include "devices/apt/apt_message.h"

namespace fovea::devices {

std::string aptLogLine(bool transmitted, std::span<const std::uint8_t> raw) {
  return std::string(transmitted ? "TX " : "RX ") + apt::toHex(raw);
}

AptFileLog::AptFileLog(const std::string& path) : out_(path, std::ios::out | std::ios::trunc) {
  if (!out_) throw std::runtime_error("cannot write the trace file '" + path + "'");
}

void AptFileLog::message(bool transmitted, std::span<const std::uint8_t> raw) {
  std::lock_guard lock(mutex_);
  out_ << aptLogLine(transmitted, raw) << '\n';
  out_.flush();
}

void AptMemoryLog::message(bool transmitted, std::span<const std::uint8_t> raw) {
  std::lock_guard lock(mutex_);
  lines_.push_back(aptLogLine(transmitted, raw));
}

std::vector<std::string> AptMemoryLog::lines() const {
  std::lock_guard lock(mutex_);
  return lines_;
}

}  // namespace fovea::devices
