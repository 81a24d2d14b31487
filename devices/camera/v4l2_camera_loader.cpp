#include <dlfcn.h>

#include <mutex>

#include "devices/camera/v4l2_camera.h"
#include "devices/transport/device_error.h"
#include "model/io/module_loader.h"

namespace fovea::devices {
namespace {

using Create = Camera* (*)(int, const char*);

#ifndef FOVEA_V4L2_CAMERA_BUILTIN
Create loadModule() {
  // Beside libfovea_devices.so (this function's library), where it is built and installed.
  const LoadedModule m = openModuleBeside(reinterpret_cast<const void*>(&loadModule), "FOVEA_V4L2_CAMERA_MODULE",
                                          "libfovea_v4l2_camera.so");
  if (m.handle == nullptr)
    throw DeviceError(DeviceError::Kind::NotFound, "cannot load the V4L2 camera module " + m.path + ": " + m.error +
                                                       (m.from_env ? " (from $FOVEA_V4L2_CAMERA_MODULE)" : ""));
  auto create = reinterpret_cast<Create>(::dlsym(m.handle, "fovea_v4l2_camera_create"));
  if (create == nullptr)
    throw DeviceError(DeviceError::Kind::NotFound, "the V4L2 camera module " + m.path + " has no camera entry point");
  return create;
}
#endif

Create creator() {
#ifdef FOVEA_V4L2_CAMERA_BUILTIN
  return &fovea_v4l2_camera_create;
#else
  static std::mutex mutex;
  static Create create = nullptr;  // a failure is not kept: each caller gets its message
  std::lock_guard lock(mutex);
  if (create == nullptr) create = loadModule();
  return create;
#endif
}

}  // namespace

std::shared_ptr<Camera> makeV4l2Camera(int index, const std::string& name) {
  return std::shared_ptr<Camera>(creator()(index, name.c_str()));
}

}  // namespace fovea::devices
