#pragma once
// The free parameters of a fit: numbers of the scene file by their JSON path
// (scene_parameters.h) with the bounds the fitter keeps them in (docs/fitting.md).
//
// Spelling (fovea-cli fit --free, the studio's list): "PATH" (default bounds), "PATH=LO:HI"
// (absolute bounds) or "PATH=+-D" (the current value +- D). Default bounds: the field table's
// range intersected with a window around the current value v: +-5 deg for angles,
// +-max(5, 0.1 |v|) mm for lengths in mm, +-25 % of |v| otherwise (+-1 when v is 0).
// Open range ends are kept out by 1e-9 of the window.

#include <string>
#include <vector>

#include "model/scene/scene.h"

namespace fovea {

struct FreeParameter {
  std::string path;  // "eye.relief_mm", "hoe_layers[1].n1", "projector.position_mm[0]"
  std::string unit;  // the field table's
  double initial = 0, lower = 0, upper = 0;
};

// Parses one spelling against the scene. Throws std::invalid_argument naming the path when it
// is not a real-valued number field of the scene (integers cannot be fitted), the bounds do not
// parse, are empty, leave the field's range, or do not contain the current value.
FreeParameter parseFreeParameter(const Scene& scene, const std::string& spec);
// All of them; a path given twice is refused.
std::vector<FreeParameter> parseFreeParameters(const Scene& scene, const std::vector<std::string>& specs);

// The scene with the free parameters set to `values` (withParameter: validated, throws
// std::invalid_argument when the scene rules refuse a combination).
Scene sceneWithValues(const Scene& scene, const std::vector<FreeParameter>& free, const std::vector<double>& values);

}  // namespace fovea
