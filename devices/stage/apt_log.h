#pragma once
// A record of every APT message on a link: one line per message, "TX " or "RX " followed by
// its bytes as upper-case hex pairs separated by single spaces (FTDI status bytes removed),
// in the order sent/received. The fovea-cli --trace contract.
#include <cstdint>
#include <fstream>
#include <mutex>
#include <span>
#include <string>
#include <vector>

namespace fovea::devices {

class AptLogSink {
 public:
  virtual ~AptLogSink() = default;
  virtual void message(bool transmitted, std::span<const std::uint8_t> raw) = 0;
};

std::string aptLogLine(bool transmitted, std::span<const std::uint8_t> raw);

class AptFileLog : public AptLogSink {
 public:
  explicit AptFileLog(const std::string& path);  // throws std::runtime_error naming the path
  void message(bool transmitted, std::span<const std::uint8_t> raw) override;

 private:
  std::mutex mutex_;
  std::ofstream out_;
};

class AptMemoryLog : public AptLogSink {
 public:
  void message(bool transmitted, std::span<const std::uint8_t> raw) override;
  std::vector<std::string> lines() const;

 private:
  mutable std::mutex mutex_;
  std::vector<std::string> lines_;
};

}  // namespace fovea::devices
