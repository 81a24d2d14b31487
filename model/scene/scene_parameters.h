#pragma once
// Scene numbers addressed by their JSON path in the scene file, for parameter sweeps
// (fovea-cli sensitivity, the studio's sensitivity analysis). The paths are those of the
// scene field table (scene_fields.h), so every number of the file format can be swept.

#include <string>
#include <vector>

#include "model/scene/scene.h"

namespace fovea {

// Sets the number at a JSON path ("eye.relief_mm", "hoe_layers[1].shrinkage_percent",
// "hoe.rotation_deg[0]") and validates the scene with the loader's rules. Throws
// std::invalid_argument naming the path or the validation errors.
Scene withParameter(const Scene& scene, const std::string& path, double value);
double parameterValue(const Scene& scene, const std::string& path);

// Every number path of `scene`, in file order ("projector.position_mm[0]", ...).
std::vector<std::string> parameterPaths(const Scene& scene);

}  // namespace fovea
