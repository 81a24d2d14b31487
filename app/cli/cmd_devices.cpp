// fovea-cli devices [--json] [--scene SCENE]: the bench hardware found (Thorlabs APT
// controllers on USB, V4L2 cameras) and the virtual devices available (one emulated
// controller per stage binding of the scene).
#include <iostream>

#include "app/cli/cli_common.h"
#include "devices/apt/stage_models.h"
#include "devices/camera/camera_enumeration.h"
#include "devices/transport/libusb_transport.h"

namespace fovea::cli {
namespace cmd_devices {  // one per command file: fovea-cli compiles in unity batches
namespace {

void install(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("devices", "List bench devices: USB stage controllers, cameras, and the virtual bench");
  auto json = std::make_shared<bool>(false);
  auto scene_path = std::make_shared<std::string>();
  cmd->add_flag("--json", *json, "print {\"devices\":[{\"kind\",\"model\",\"serial\",\"virtual\"},...]}");
  cmd->add_option("--scene", *scene_path, "scene whose stage bindings define the virtual bench (default: prototype)");
  cmd->callback([json, scene_path] {
    const Scene scene = loadSceneOrExit(*scene_path);
    nlohmann::json list = nlohmann::json::array();
    std::string usb_error;
    for (const auto& d : devices::enumerateUsbControllers(&usb_error))
      list.push_back({{"kind", d.kind},
                      {"model", d.model},
                      {"serial", d.serial},
                      {"virtual", false},
                      {"description", d.description}});
    for (const auto& c : devices::enumerateV4l2()) {
      const auto d = devices::toDeviceInfo(c);
      list.push_back({{"kind", d.kind},
                      {"model", d.model},
                      {"serial", d.serial},
                      {"virtual", false},
                      {"description", d.description},
                      {"index", c.index}});
    }
    for (const auto& b : scene.stages) {
      const auto stage = apt::findStage(b.stage_model);
      list.push_back({{"kind", "stage-controller"},
                      {"model", b.controller},
                      {"serial", b.serial},
                      {"virtual", true},
                      {"stage_model", b.stage_model},
                      {"unit", stage ? stage->unit() : "mm"},
                      {"element", b.element},
                      {"axis", b.axis},
                      {"channel", b.channel}});
    }
    // The virtual bench's camera (frames from a renderer on the bench clock).
    list.push_back({{"kind", "camera"},
                    {"model", "virtual-eye-camera"},
                    {"serial", "VCAM0001"},
                    {"virtual", true},
                    {"description", "virtual camera at the eye position"}});
    if (*json) {
      nlohmann::json out{{"devices", list}};
      if (!usb_error.empty()) out["usb_error"] = usb_error;
      printJson(out);
      return;
    }
    if (!usb_error.empty()) std::cerr << "warning: " << usb_error << "\n";
    for (const auto& d : list) {
      std::cout << (d["virtual"].get<bool>() ? "virtual  " : "hardware ") << d["kind"].get<std::string>() << "  "
                << d["model"].get<std::string>() << "  " << d["serial"].get<std::string>();
      if (d.contains("element") && d.contains("stage_model"))
        std::cout << "  (" << d["stage_model"].get<std::string>() << " -> " << d["element"].get<std::string>() << "."
                  << d["axis"].get<std::string>() << ")";
      std::cout << "\n";
    }
  });
}

const Registrar reg{"devices", &install};

}  // namespace
}  // namespace cmd_devices
}  // namespace fovea::cli
