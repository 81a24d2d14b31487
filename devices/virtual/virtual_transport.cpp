#include "devices/virtual/virtual_transport.h"

#include "devices/transport/device_error.h"

namespace fovea::devices {

VirtualTransport::VirtualTransport(std::shared_ptr<VirtualAptController> controller, std::shared_ptr<Clock> clock)
    : controller_(std::move(controller)), clock_(std::move(clock)) {}

void VirtualTransport::open() {
  if (unplugged_)
    throw DeviceError(DeviceError::Kind::NotFound,
                      "virtual controller " + controller_->config().serial + " is unplugged");
  open_ = true;
  notifyEvent(TransportEvent::Connected);
}

void VirtualTransport::write(std::span<const std::uint8_t> bytes) {
  if (!isOpen())
    throw DeviceError(DeviceError::Kind::Disconnected,
                      "virtual controller " + controller_->config().serial + " is disconnected");
  controller_->receive(bytes);
}

std::vector<std::uint8_t> VirtualTransport::read(std::chrono::milliseconds timeout) {
  if (!isOpen())
    throw DeviceError(DeviceError::Kind::Disconnected,
                      "virtual controller " + controller_->config().serial + " is disconnected");
  auto out = controller_->takeOutput();
  if (!out.empty()) return out;
  const double deadline = clock_->now() + std::chrono::duration<double>(timeout).count();
  clock_->waitUntil(std::min(deadline, controller_->nextEventTime()));
  if (unplugged_)
    throw DeviceError(DeviceError::Kind::Disconnected,
                      "virtual controller " + controller_->config().serial + " is disconnected");
  return controller_->takeOutput();
}

DeviceInfo VirtualTransport::info() const {
  DeviceInfo i;
  i.model = controller_->config().controller.name;
  i.serial = controller_->config().serial;
  i.description = "virtual " + controller_->config().controller.name + " with " + controller_->config().stage.name;
  i.is_virtual = true;
  return i;
}

void VirtualTransport::simulateUnplug() {
  unplugged_ = true;
  notifyEvent(TransportEvent::Disconnected);
}

void VirtualTransport::replug() {
  unplugged_ = false;
  notifyEvent(TransportEvent::Connected);
}

std::shared_ptr<VirtualAptController> makeVirtualController(const std::string& model, const std::string& serial,
                                                            std::shared_ptr<Clock> clock) {
  VirtualControllerConfig cfg;
  auto stage = apt::findStage(model);
  auto controller = apt::findController(model);
  if (stage && !controller) {
    // A stage name: its usual controller (Z8 actuators on a KDC101, DDS on a KBD101).
    for (const auto& c : apt::controllerModels())
      if (c.default_stage == stage->name) controller = c;
  }
  if (controller && !stage) stage = apt::findStage(controller->default_stage);
  if (!stage || !controller)
    throw DeviceError(DeviceError::Kind::Usage,
                      "unknown stage or controller model '" + model +
                          "' (known: MTS25-Z8, Z825B, DDSM50, K10CR1, KDC101, TDC001, KBD101)");
  cfg.controller = *controller;
  cfg.stage = *stage;
  cfg.serial = serial.empty() ? controller->serial_prefix + "000001" : serial;
  return std::make_shared<VirtualAptController>(cfg, std::move(clock));
}

}  // namespace fovea::devices
