#pragma once
// --eye left|right|both: an analysis per eye of a binocular scene (issue 30;
// model/scene/eye_scene.h). Shared by trace, sweep, compare-shift, selectivity and resolution.
//
// Without --eye a monocular scene runs as it always did (its JSON unchanged) and a binocular
// scene runs both eyes. --eye on a monocular scene is a usage error (exit 2): it has one eye.
// JSON: one eye gives that eye's usual document plus "eye": "left"|"right"; both give the right
// eye's document (the scene's own train: every key a monocular run has) plus
// "eyes": {"left": {...}, "right": {...}}, each eye's usual document.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "model/scene/eye_scene.h"
#include "model/scene/scene.h"

namespace fovea::cli {

// Adds --eye to `cmd`; the returned text is empty when the option was not given.
std::shared_ptr<std::string> addEyeOption(CLI::App* cmd);

// One scene to analyse: an eye of a binocular scene, or (side empty) the monocular scene.
struct EyeRun {
  std::optional<EyeSide> side;
  Scene scene;
};

// The runs for `eye` ("" = not given, "left", "right", "both"), left before right.
// `scene_name` names the scene in the usage error for --eye on a monocular scene.
std::vector<EyeRun> eyeRuns(const Scene& scene, const std::string& eye, const std::string& scene_name);

// The document of the runs from one document per run (same order), as in the header comment.
nlohmann::json combineEyeDocuments(const std::vector<EyeRun>& runs, const std::vector<nlohmann::json>& docs);

// "left eye: " / "right eye: " for text output; "" for a monocular run.
std::string eyePrefix(const EyeRun& run);

}  // namespace fovea::cli
