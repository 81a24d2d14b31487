#pragma once
// Transport over libusb to an FTDI-based Thorlabs controller (KDC101, TDC001, KBD101,
// K10CR1: VID 0x0403, PID 0xFAF0), selected by serial number.
//
// One I/O thread per device owns the libusb context and handle: it opens and configures the
// FTDI bridge (reset, purge RX/TX, 115200 baud 8N1, RTS/CTS, RTS high, 2 ms latency timer),
// drains the write queue with bulk OUT transfers and polls bulk IN, removing the two FTDI
// status bytes of every max-packet chunk. read()/write() only touch the queues.
#include <atomic>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <string>
#include <thread>

#include "devices/transport/transport.h"

namespace fovea::devices {

class LibusbTransport : public Transport {
 public:
  explicit LibusbTransport(std::string serial);
  ~LibusbTransport() override;
  LibusbTransport(const LibusbTransport&) = delete;
  LibusbTransport& operator=(const LibusbTransport&) = delete;

  void open() override;
  void close() override;
  bool isOpen() const override;
  void write(std::span<const std::uint8_t> bytes) override;
  std::vector<std::uint8_t> read(std::chrono::milliseconds timeout) override;
  DeviceInfo info() const override;

 private:
  void ioThread();

  std::string serial_;
  DeviceInfo info_;
  std::thread io_;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<std::uint8_t> rx_;
  std::deque<std::vector<std::uint8_t>> tx_;
  std::atomic<bool> stop_{false};
  bool ready_ = false, failed_ = false, disconnected_ = false, open_ = false;
  std::string error_;
};

// Thorlabs controllers on the USB bus. Model from the serial prefix, else the product
// string. Returns an empty list (never throws) when libusb cannot start; `error` says why.
std::vector<DeviceInfo> enumerateUsbControllers(std::string* error = nullptr);

// Watches the bus for Thorlabs controllers arriving and leaving: libusb hot-plug callbacks
// where the platform has them (libusb_has_capability), a 1 s enumeration poll otherwise.
class UsbHotplugMonitor {
 public:
  using Callback = std::function<void(TransportEvent, const DeviceInfo&)>;
  explicit UsbHotplugMonitor(Callback callback);
  ~UsbHotplugMonitor();
  bool usesHotplugCallbacks() const { return hotplug_; }

 private:
  void run();
  Callback callback_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> changed_{true};
  bool hotplug_ = false;
};

}  // namespace fovea::devices
