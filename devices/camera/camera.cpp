#include "devices/camera/camera.h"

#include "devices/transport/device_error.h"

namespace fovea::devices {

void Camera::setExposure(double) {
  throw DeviceError(DeviceError::Kind::Usage, info().model + " offers no exposure control");
}

void Camera::setGain(double) {
  throw DeviceError(DeviceError::Kind::Usage, info().model + " offers no gain control");
}

SettledCapture captureSettled(Camera& camera, double settled_at_s, int max_frames) {
  SettledCapture out;
  for (int i = 0; i <= max_frames; ++i) {
    Frame f = camera.grab();
    if (frameIsFresh(f, settled_at_s)) {
      out.frame = std::move(f);
      return out;
    }
    ++out.discarded;
  }
  throw DeviceError(DeviceError::Kind::Timeout, camera.info().model +
                                                    ": no frame exposed after the stage settled within " +
                                                    std::to_string(max_frames) + " frames");
}

}  // namespace fovea::devices
