#pragma once
// A byte pipe to one motion controller: the libusb FTDI link of a real Thorlabs cube, or
// the APT emulator of the virtual bench. The APT layers above never know which.
//
// Threading: a Transport is used from one thread at a time (its owner). Implementations
// that need background I/O own their handle on their own thread; nothing is shared.
#include <chrono>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace fovea::devices {

enum class TransportEvent { Connected, Disconnected };

struct DeviceInfo {
  std::string kind = "stage-controller";  // "stage-controller" or "camera"
  std::string model;                      // "KDC101", "K10CR1", ...
  std::string serial;
  std::string description;  // USB product string or emulator description
  bool is_virtual = false;
};

class Transport {
 public:
  virtual ~Transport() = default;
  virtual void open() = 0;  // throws DeviceError (NotFound, Io)
  virtual void close() = 0;
  virtual bool isOpen() const = 0;
  // Queues bytes for the device. Throws DeviceError(Disconnected) when the device is gone.
  virtual void write(std::span<const std::uint8_t> bytes) = 0;
  // Bytes received (FTDI status bytes already removed), waiting up to `timeout` for the
  // first; empty on timeout. Throws DeviceError(Disconnected) when the device is gone.
  virtual std::vector<std::uint8_t> read(std::chrono::milliseconds timeout) = 0;
  // Connection events, called from the transport's owner thread or its I/O thread.
  virtual void setEventCallback(std::function<void(TransportEvent)> callback) { callback_ = std::move(callback); }
  virtual DeviceInfo info() const = 0;
  // Seconds on the link's clock (timeouts are measured on it): the steady clock for real
  // devices, the simulated clock of a virtual bench.
  virtual double now() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  }

 protected:
  void notifyEvent(TransportEvent e) {
    if (callback_) callback_(e);
  }
  std::function<void(TransportEvent)> callback_;
};

}  // namespace fovea::devices
