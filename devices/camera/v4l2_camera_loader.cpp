#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "devices/camera/v4l2_camera.h"
#include "devices/transport/device_error.h"

namespace fovea::devices {
namespace {

using Create = Camera* (*)(int, const char*);

#ifndef FOVEA_V4L2_CAMERA_BUILTIN
// The folder of the shared object this function is in (libfovea_devices.so): the module is
// built and installed beside it.
std::filesystem::path devicesLibraryFolder() {
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&devicesLibraryFolder), &info) == 0 || info.dli_fname == nullptr) return {};
  return std::filesystem::path(info.dli_fname).parent_path();
}

Create loadModule() {
  const char* given = std::getenv("FOVEA_V4L2_CAMERA_MODULE");
  const std::string path = given != nullptr && *given != '\0'
                               ? std::string(given)
                               : (devicesLibraryFolder() / "libfovea_v4l2_camera.so").string();
  void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // kept for the process's life
  if (handle == nullptr) {
    const char* why = ::dlerror();
    throw DeviceError(DeviceError::Kind::NotFound,
                      "cannot load the V4L2 camera module " + path + ": " + (why != nullptr ? why : "unknown error"));
  }
  auto create = reinterpret_cast<Create>(::dlsym(handle, "fovea_v4l2_camera_create"));
  if (create == nullptr)
    throw DeviceError(DeviceError::Kind::NotFound, "the V4L2 camera module " + path + " has no camera entry point");
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
