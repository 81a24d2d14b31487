#include "devices/camera/virtual_eye_renderer.h"

#include <utility>

namespace fovea::devices {

VirtualCamera::Renderer virtualEyeRenderer(const Scene& scene, GazeSource gaze, const VirtualEyeOptions& options) {
  gaze::EyeAppearance eye;
  eye.pupil_diameter_mm = scene.eye.pupil_diameter_mm;
  gaze::EyeFrameSpec spec;
  spec.leds_mm = gaze::ledRing(options.camera, options.leds, options.led_ring_radius_mm);
  spec.noise_sigma = 0;  // the camera adds it
  spec.seed = options.seed;
  return [camera = options.camera, eye, spec, source = std::move(gaze)](double t_s) mutable {
    spec.gaze_deg = source(t_s);
    cv::Mat radiance;
    gaze::renderEyeFrame(camera, eye, spec).image.convertTo(radiance, CV_32F, 1.0 / 255.0);
    return radiance;
  };
}

}  // namespace fovea::devices
