// fovea-cli fit-targets MANIFEST [--sigma-mm S] [--source TEXT] [--out FILE] --json: a capture
// session's manifest (the capture wizard's manifest.json, or its folder) as a targets file for
// `fovea-cli fit` (devices/calibration/manifest_targets.h: x_p per gaze of a geometric session).
#include <cmath>
#include <filesystem>
#include <iostream>

#include "app/cli/cli_common.h"
#include "devices/calibration/manifest_targets.h"
#include "model/io/json_input.h"
#include "model/scene/scene_io.h"

namespace fovea::cli {
namespace cmd_fit_targets {  // one per command file: fovea-cli compiles in unity batches
namespace {

struct Args {
  std::string manifest, out, source = "bench";
  double sigma_mm = 0.05;
  bool json = false;
};

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("fit-targets", "Turn a capture session's manifest into a targets file for `fit`");
  auto a = std::make_shared<Args>();
  cmd->add_option("MANIFEST", a->manifest, "manifest.json of a capture session, or its folder")->required();
  cmd->add_option("--sigma-mm", a->sigma_mm, "uncertainty of each x_p (default 0.05 mm)");
  cmd->add_option("--source", a->source, "source of the targets (default \"bench\"; the step id is added)");
  auto* out = cmd->add_option("--out", a->out, "also write the targets file here");
  cmd->add_flag("--json", a->json, "print the targets file (JSON) with the captures skipped");
  cmd->callback([a, out] {
    checkOutputOption(out, a->out);
    if (!std::isfinite(a->sigma_mm) || !(a->sigma_mm > 0))
      usageError("--sigma-mm: must be a finite number > 0, got " + std::to_string(a->sigma_mm));
    std::filesystem::path path = a->manifest;
    if (std::filesystem::is_directory(path)) path /= "manifest.json";
    nlohmann::json m;
    try {
      m = readJsonFile(path);
    } catch (const std::exception& e) {
      inputError(e.what());
    }
    devices::ManifestTargets t;
    try {
      t = devices::fitTargetsFromManifest(m, {a->sigma_mm, a->source});
    } catch (const std::invalid_argument& e) {
      inputError(path.string() + ": " + e.what());
    }
    if (t.targets.empty())
      inputError(path.string() + ": no target in this session" +
                 (t.skipped.empty() ? std::string() : " (" + t.skipped.front() + ")"));
    nlohmann::json doc = fitTargetsJson(t.targets, "from the capture session " + path.string());
    if (!a->out.empty()) {
      try {
        writeFileAtomic(a->out, doc.dump(2) + "\n");
      } catch (const std::exception& e) {
        inputError("--out: " + std::string(e.what()));
      }
    }
    doc["skipped"] = t.skipped;
    if (a->json) {
      printJson(doc);
      return;
    }
    for (const auto& x : t.targets)
      std::cout << x.id << ": x_p " << x.value << " +- " << x.sigma << " mm at " << x.parameters["gaze_deg"]
                << " deg\n";
    for (const auto& s : t.skipped) std::cerr << "skipped: " << s << "\n";
  });
}

const Registrar reg{"fit-targets", &install};

}  // namespace
}  // namespace cmd_fit_targets
}  // namespace fovea::cli
