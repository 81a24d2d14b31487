#pragma once
// The Transport of the virtual bench: bytes go to a VirtualAptController instead of USB.
// read() lets clock time pass up to its timeout (a simulated clock jumps straight to the
// next reply, so a 4 s move takes no wall time in tests). simulateUnplug() makes the link
// vanish like a pulled cable; the controller keeps its state (a cube keeps running on its
// own supply), and replug() brings the link back.
#include <atomic>
#include <memory>

#include "devices/transport/transport.h"
#include "devices/virtual/virtual_controller.h"

namespace fovea::devices {

class VirtualTransport : public Transport {
 public:
  VirtualTransport(std::shared_ptr<VirtualAptController> controller, std::shared_ptr<Clock> clock);
  void open() override;
  void close() override { open_ = false; }
  bool isOpen() const override { return open_ && !unplugged_; }
  void write(std::span<const std::uint8_t> bytes) override;
  std::vector<std::uint8_t> read(std::chrono::milliseconds timeout) override;
  DeviceInfo info() const override;
  double now() const override { return clock_->now(); }

  void simulateUnplug();
  void replug();
  VirtualAptController& controller() { return *controller_; }
  Clock& clock() { return *clock_; }

 private:
  std::shared_ptr<VirtualAptController> controller_;
  std::shared_ptr<Clock> clock_;
  std::atomic<bool> open_{false}, unplugged_{false};
};

// The virtual bench: one emulated controller per stage model, with the scene's serials.
std::shared_ptr<VirtualAptController> makeVirtualController(const std::string& stage_or_controller_model,
                                                            const std::string& serial, std::shared_ptr<Clock> clock);

}  // namespace fovea::devices
