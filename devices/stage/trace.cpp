#include "devices/stage/trace.h"

#include <stdexcept>

#include "devices/apt/apt_message.h"

namespace fovea::devices {

std::string traceLine(bool transmitted, std::span<const std::uint8_t> raw) {
  return std::string(transmitted ? "TX " : "RX ") + apt::toHex(raw);
}

FileTrace::FileTrace(const std::string& path) : out_(path, std::ios::out | std::ios::trunc) {
  if (!out_) throw std::runtime_error("cannot write the trace file '" + path + "'");
}

void FileTrace::message(bool transmitted, std::span<const std::uint8_t> raw) {
  std::lock_guard lock(mutex_);
  out_ << traceLine(transmitted, raw) << '\n';
  out_.flush();
}

void MemoryTrace::message(bool transmitted, std::span<const std::uint8_t> raw) {
  std::lock_guard lock(mutex_);
  lines_.push_back(traceLine(transmitted, raw));
}

std::vector<std::string> MemoryTrace::lines() const {
  std::lock_guard lock(mutex_);
  return lines_;
}

}  // namespace fovea::devices
