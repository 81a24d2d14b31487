#pragma once
// The scene's elements as VTK actors at their real size and pose, built from the model's
// Scene and frames (model/scene/scene_geometry.h). The view reads the model; it computes
// no physics.
//   HOE: the carrier plate with one slab per layer, coloured by its recording wavelength
//        (layer thickness and spacing drawn exaggerated to at least kMinDrawnLayer_mm so the
//        micrometre films are visible; lateral size is real).
//   Projector: a body behind its exit pupil; the projection frustum up to the HOE plane as a
//              faint outline in its own layer ("frustum", so views can hide the light).
//   Eye: a muted half-transparent eyeball, iris and pupil (dark, the scene's pupil diameter)
//        discs, and the optical axis along the gaze.
//   Foveal display: the micro-OLED panel and its image combiner on the eye's axis.
//   Beam-shaping lens: a lens body from its focal length, index and thickness with its rim
//   drawn as a ring (ghosted when disabled).
//   Translation stages: the travel between the soft limits along the driven axis, in their own
//   layer ("stages": mechanics, not optics, which the eye's view hides).

#include <array>

#include "model/scene/scene.h"
#include "viz/scene_layer.h"

namespace fovea::viz {

inline constexpr double kMinDrawnLayer_mm = 0.3;
inline constexpr double kFrustumOpacity = 0.35;  // the projection outline: present, never dominant
inline constexpr double kEyeballOpacity = 0.45;

// Colours of the actors (RGB, 0..1); tests look for them in screenshots.
namespace colors {
inline constexpr std::array<double, 3> kProjectorBody{0.30, 0.32, 0.36};
inline constexpr std::array<double, 3> kProjectorFrustum{1.00, 0.78, 0.20};
inline constexpr std::array<double, 3> kEyeball{0.72, 0.70, 0.66};
inline constexpr std::array<double, 3> kIris{0.25, 0.45, 0.75};
inline constexpr std::array<double, 3> kPupil{0.03, 0.03, 0.03};
inline constexpr std::array<double, 3> kOpticalAxis{0.20, 0.95, 0.35};
inline constexpr std::array<double, 3> kMicroOled{0.05, 0.75, 0.75};
inline constexpr std::array<double, 3> kCombiner{0.60, 0.85, 1.00};
inline constexpr std::array<double, 3> kLens{0.45, 0.70, 1.00};
inline constexpr std::array<double, 3> kLensRim{0.60, 0.85, 1.00};
inline constexpr std::array<double, 3> kSubstrate{0.75, 0.75, 0.80};
inline constexpr std::array<double, 3> kStage{0.85, 0.35, 0.85};
inline constexpr std::array<double, 3> kSelection{1.00, 1.00, 0.00};
}  // namespace colors

// Adds every element's actors to `layer`, the projector's light (frustum outline) to `light`
// and the translation stages' travel to `stages` (all cleared by the caller).
void buildSceneActors(const Scene& scene, SceneLayer& layer, SceneLayer& light, SceneLayer& stages);
// Adds the eye's actors only (element "eye"): what a gaze change redraws.
void buildEyeActors(const Scene& scene, SceneLayer& layer);

}  // namespace fovea::viz
