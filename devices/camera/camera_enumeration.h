#pragma once
// V4L2 video capture devices (/dev/videoN), listed from sysfs without opening them.
#include <string>
#include <vector>

#include "devices/transport/transport.h"

namespace fovea::devices {

struct V4l2Device {
  int index = 0;            // N of /dev/videoN (OpenCV VideoCapture index)
  std::string name;         // sysfs "name"
  std::string device_path;  // "/dev/video0"
};

// Capture nodes only: a camera exposes extra metadata nodes (index attribute != 0) that
// cannot deliver frames; those are skipped. `sysfs_root` is for tests.
std::vector<V4l2Device> enumerateV4l2(const std::string& sysfs_root = "/sys/class/video4linux");
DeviceInfo toDeviceInfo(const V4l2Device& d);

}  // namespace fovea::devices
