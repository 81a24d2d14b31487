#pragma once
// The live bench of a scene: one AxisWorker per stage binding. A binding whose controller
// (by serial) is on the USB bus drives the hardware; the others run on the virtual bench,
// marked as virtual, so the studio works with no hardware at all.
#include <future>
#include <memory>
#include <vector>

#include "devices/bench/axis_worker.h"
#include "devices/virtual/sim_clock.h"
#include "devices/virtual/virtual_transport.h"
#include "model/scene/scene.h"

namespace fovea::devices {

struct BenchOptions {
  bool use_hardware = true;              // bind to USB controllers found by serial
  std::shared_ptr<Clock> virtual_clock;  // default: the steady clock (real-time moves)
  std::chrono::milliseconds idle_poll{200};
  std::chrono::milliseconds reconnect_interval{1000};
};

class Bench {
 public:
  // `usb` lists the controllers present (default: enumerate the bus).
  Bench(const Scene& scene, BenchOptions options = {}, std::optional<std::vector<DeviceInfo>> usb = std::nullopt);
  ~Bench();

  std::vector<AxisWorker*> axes();
  AxisWorker* find(const std::string& element, const std::string& axis);
  bool anyVirtual() const;
  std::shared_ptr<VirtualAptController> virtualController(const std::string& element, const std::string& axis);
  VirtualTransport* virtualLink(const std::string& element, const std::string& axis);  // unplug simulation

  std::vector<std::future<void>> connectAll();
  // Moves an element coordinate (mm or deg, the scene's frame): stage target = value -
  // home_offset, checked against the binding's soft limits before anything is sent.
  std::future<void> moveElement(const std::string& element, const std::string& axis, double value);
  // Immediate stop on every axis (Esc in the studio).
  void emergencyStopAll();

 private:
  struct Axis {
    std::unique_ptr<AxisWorker> worker;
    std::shared_ptr<VirtualAptController> emulator;  // null for hardware
    VirtualTransport* link = nullptr;                // owned by the worker's Stage
  };
  std::vector<Axis> axes_;
};

}  // namespace fovea::devices
