#include "devices/bench/bench.h"

#include "devices/stage/stage_binding.h"
#include "devices/transport/libusb_transport.h"

namespace fovea::devices {

Bench::Bench(const Scene& scene, BenchOptions options, std::optional<std::vector<DeviceInfo>> usb) {
  if (!options.virtual_clock) options.virtual_clock = std::make_shared<SteadyClock>();
  if (options.use_hardware && !usb) usb = enumerateUsbControllers();
  for (const auto& b : scene.stages) {
    const StageConfig config = stageConfigForBinding(b);
    bool present = false;
    if (options.use_hardware && usb)
      for (const auto& d : *usb) present = present || (!d.is_virtual && d.serial == b.serial);
    Axis axis;
    std::unique_ptr<Transport> transport;
    if (present) {
      transport = std::make_unique<LibusbTransport>(b.serial);
    } else {
      VirtualControllerConfig vc;
      vc.controller = config.controller;
      vc.stage = config.stage;
      vc.serial = b.serial.empty() ? config.controller.serial_prefix + "000001" : b.serial;
      // Power-on at the scene's nominal pose (element coordinate 0), homed.
      vc.position = std::clamp(elementToStage(b, 0.0), config.soft_min, config.soft_max);
      axis.emulator = std::make_shared<VirtualAptController>(vc, options.virtual_clock);
      auto link = std::make_unique<VirtualTransport>(axis.emulator, options.virtual_clock);
      axis.link = link.get();
      transport = std::move(link);
    }
    auto stage = std::make_unique<Stage>(std::move(transport), config);
    axis.worker =
        std::make_unique<AxisWorker>(std::move(stage), b, !present, options.idle_poll, options.reconnect_interval);
    axes_.push_back(std::move(axis));
  }
}

Bench::~Bench() = default;

std::vector<AxisWorker*> Bench::axes() {
  std::vector<AxisWorker*> out;
  for (auto& a : axes_) out.push_back(a.worker.get());
  return out;
}

AxisWorker* Bench::find(const std::string& element, const std::string& axis) {
  for (auto& a : axes_)
    if (a.worker->binding().element == element && a.worker->binding().axis == axis) return a.worker.get();
  return nullptr;
}

bool Bench::anyVirtual() const {
  for (const auto& a : axes_)
    if (a.emulator) return true;
  return false;
}

std::shared_ptr<VirtualAptController> Bench::virtualController(const std::string& element, const std::string& axis) {
  for (auto& a : axes_)
    if (a.worker->binding().element == element && a.worker->binding().axis == axis) return a.emulator;
  return nullptr;
}

VirtualTransport* Bench::virtualLink(const std::string& element, const std::string& axis) {
  for (auto& a : axes_)
    if (a.worker->binding().element == element && a.worker->binding().axis == axis) return a.link;
  return nullptr;
}

std::vector<std::future<void>> Bench::connectAll() {
  std::vector<std::future<void>> out;
  for (auto& a : axes_) out.push_back(a.worker->submit([](Stage& s) { s.connect(); }));
  return out;
}

std::future<void> Bench::moveElement(const std::string& element, const std::string& axis, double value) {
  AxisWorker* w = find(element, axis);
  if (!w) {
    std::promise<void> p;
    p.set_exception(std::make_exception_ptr(
        DeviceError(DeviceError::Kind::Usage, "the scene binds no stage to " + element + "." + axis)));
    return p.get_future();
  }
  const double target = elementToStage(w->binding(), value);
  return w->submit([target](Stage& s) { s.moveAbsolute(target); });
}

void Bench::emergencyStopAll() {
  for (auto& a : axes_) a.worker->emergencyStop();
}

}  // namespace fovea::devices
