#pragma once
// A V4L2 camera (devices/camera/v4l2/opencv_camera.h: OpenCV's VideoCapture). OpenCV's videoio
// loads ~240 libraries (GStreamer, FFmpeg, ...) that cost every process linking it ~0.05 CPU-s at
// start-up, so the camera is a module of its own (libfovea_v4l2_camera.so beside
// libfovea_devices.so), loaded when the first real camera is made (issue 25). A static build
// (FOVEA_SHARED_LIBS=OFF) compiles it in.
#include <memory>
#include <string>

#include "devices/camera/camera.h"

namespace fovea::devices {

// The camera /dev/video<index>, not opened yet. The module comes from
// $FOVEA_V4L2_CAMERA_MODULE when set, else from the folder of the library holding the devices
// code; a module that cannot be loaded is a DeviceError (NotFound) naming its path and the
// loader's reason.
std::shared_ptr<Camera> makeV4l2Camera(int index, const std::string& name = {});

}  // namespace fovea::devices

extern "C" fovea::devices::Camera* fovea_v4l2_camera_create(
    int index, const char* name);  // NOLINT(readability-identifier-naming): C ABI name
