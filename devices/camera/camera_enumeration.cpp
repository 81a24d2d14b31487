#include "devices/camera/camera_enumeration.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace fovea::devices {

namespace {
std::string readLine(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::string s;
  std::getline(in, s);
  return s;
}
}  // namespace

std::vector<V4l2Device> enumerateV4l2(const std::string& sysfs_root) {
  std::vector<V4l2Device> out;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(sysfs_root, ec)) {
    const std::string node = entry.path().filename().string();
    if (node.rfind("video", 0) != 0) continue;
    int n = -1;
    try {
      n = std::stoi(node.substr(5));
    } catch (const std::exception&) {
      continue;
    }
    const std::string index = readLine(entry.path() / "index");
    if (!index.empty() && index != "0") continue;  // metadata node of a camera
    out.push_back({n, readLine(entry.path() / "name"), "/dev/" + node});
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.index < b.index; });
  return out;
}

DeviceInfo toDeviceInfo(const V4l2Device& d) {
  DeviceInfo i;
  i.kind = "camera";
  i.model = d.name.empty() ? "V4L2 camera" : d.name;
  i.serial = d.device_path;
  i.description = "V4L2 capture device " + d.device_path;
  return i;
}

}  // namespace fovea::devices
