#pragma once
// The virtual bench's IR eye camera: a VirtualCamera renderer that draws the eye of the
// scene (model/gaze/eye_image_renderer.h: its pupil diameter, the gaze from a source of the
// bench time) as a headset's eye camera sees it, so the pupil tracker, the wizard's gaze
// session and the studio's camera view all see the same synthetic frames. The
// VirtualCamera adds its own sensor noise, exposure and gain; the renderer draws no noise.
#include <array>
#include <functional>

#include "devices/camera/virtual_camera.h"
#include "model/gaze/eye_image_renderer.h"
#include "model/scene/scene.h"

namespace fovea::devices {

using GazeSource = std::function<std::array<double, 2>(double t_s)>;

struct VirtualEyeOptions {
  gaze::IrCameraPose camera;
  int leds = 6;
  double led_ring_radius_mm = 10;
  unsigned seed = 1;  // iris texture and lashes (fixed for the session: one eye)
};

VirtualCamera::Renderer virtualEyeRenderer(const Scene& scene, GazeSource gaze, const VirtualEyeOptions& options = {});

}  // namespace fovea::devices
