#pragma once
// Tracing the peripheral display: projector rays -> recorded HOE stack (Kogelnik, every layer on
// every wavelength) -> eye pupil -> retinal FOV. Shared contract (BRIEF.md): the names and
// meanings below are fixed; members may be added.
//
// Model (docs/physics.md):
//  - rays: projectorRays() over the projector FOV, ~`rays` per wavelength, from the projector
//    position shifted by source_shift_mm along bench z;
//  - the plate moves by hoe_shift_mm along its local x, y; the fringes move with it (each plate
//    point keeps the grating recorded at it with the plate at its nominal pose); the eye and
//    the projector stay (the eye is placed from the nominal HOE pose, placeEye());
//  - the layers are met in depth order along the probe; all sit in the plate plane for the
//    geometry (their µm offsets only order them). Layer i sees the power left in the zero
//    order of the layers before it (chained); its diffracted power leaves without further
//    interaction. A ray's efficiency is the sum of the diffracted powers that leave the stack
//    (not evanescent, not trapped by TIR); its out_direction is that of the layer diffracting
//    most (cross-talk of the other layers is counted in the efficiency, not in the direction);
//  - a ray enters the eye when its straight path after the HOE crosses the pupil disc; its
//    visual angle is the arrival direction in the eye frame (fieldAngleDeg());
//  - FOV over the accepted rays (in the pupil, efficiency >= threshold):
//      horizontal = max - min of the field yaw, vertical = max - min of the field pitch,
//      diagonal   = the larger angle between the two rays extreme along yaw + pitch and the
//                   two rays extreme along yaw - pitch (true 3-D angle between directions).
//  - mean_efficiency: mean efficiency of the rays entering the pupil (0 if none).
//
// Computation (trace_pipeline.h): a graph of memoised stages, each keyed by a hash of exactly
// the inputs it reads (geometry -> recording per layer -> diffraction and coupled wave per
// layer and wavelength -> stack per wavelength -> pupil -> FOV -> analyses). traceScene()
// runs a fresh pipeline; keep a TracePipeline to reuse stages between calls (gaze updates).

#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "model/physics/grating.h"
#include "model/scene/scene.h"

namespace fovea {

struct TraceOptions {
  std::optional<std::array<double, 2>> gaze_deg;  // yaw, pitch; default: scene.eye.gaze_deg
  std::array<double, 2> hoe_shift_mm{0.0, 0.0};   // lateral HOE shift (HOE local x, y)
  double source_shift_mm = 0.0;                   // projector point-source shift along bench z
  std::optional<double> wavelength_nm;            // trace only this wavelength (default: all projector wavelengths)
  int rays = 4000;                                // approximate rays per wavelength over the projector FOV
  double efficiency_threshold = 0.1;              // rays below it do not count for the FOV
  bool keep_rays = false;                         // fill TraceResult::ray_list (drawing)
  Polarization polarization = Polarization::Unpolarized;  // projector light (scene has no polarisation)
  // Skip the coupled-wave step for rays whose every diffracted order misses the pupil (they
  // cannot count for the FOV, rays_in_pupil or mean_efficiency; TracedRay::culled is set). The
  // whole-plate statistics (mean_efficiency_on_hoe) are then not computed (NaN).
  bool cull_to_pupil = false;
  bool keep_field_rays = false;  // fill TraceResult::field_rays (TracePipeline only; cheaper than keep_rays)
};

// Rays per wavelength for interactive work. The least that hold the prototype's retinal FOV
// to 0.1 deg of its converged value is 64 000 (docs/benchmarks.md, "Ray count vs FOV error"),
// but at 64 000 a gaze update that also builds the per-ray list the studio draws takes far
// more than the 16 ms target (`fovea-cli bench`: gaze_update_keep_rays_ms_64k_per_wavelength_1core),
// so this stays at 20 000 until that list gets cheaper. Nothing reads it yet: the studio's
// Display panel starts at 4 000 rays/λ (widgets/display_panel.cpp).
inline constexpr int kInteractiveRays = 20000;

struct FovDeg {
  double horizontal = 0, vertical = 0, diagonal = 0;
};

struct TracedRay {
  Eigen::Vector3d source, hoe_point, out_direction;  // bench frame, mm; unit direction after the HOE
  double wavelength_nm = 0, efficiency = 0;          // efficiency summed over the layers that diffract it
  bool hits_hoe = false, in_pupil = false, evanescent = false;
  std::array<double, 2> field_deg{0, 0};  // visual angle (yaw, pitch) relative to the gaze
  // Additions:
  Eigen::Vector3d projector_direction = Eigen::Vector3d::Zero();  // unit direction leaving the projector
  bool exits = false;          // some diffracted light leaves the stack (out_direction valid)
  bool towards_eye = false;    // out_direction heads to the eye side of the plate
  bool tir = false;            // the dominant order is trapped by total internal reflection
  int layer = -1;              // index of the dominant layer in scene.hoe_layers (-1: none)
  double xi = 0, nu = 0;       // Kogelnik parameters of the dominant layer
  double pupil_radius_mm = 0;  // where it crosses the pupil plane, from the pupil centre
  std::array<int, 2> pixel{0, 0};
  bool culled = false;  // cull_to_pupil skipped its coupled-wave step (efficiency not computed)
};

// A ray on the plate reduced to what the gaze studies' continuous FOV reads
// (trace_evaluator.h): the same values as its TracedRay.
struct FieldRay {
  double wavelength_nm = 0, efficiency = 0;
  std::array<int, 2> pixel{0, 0};
  std::array<double, 2> field_deg{0, 0};  // set when in_pupil
  bool in_pupil = false;
};

struct WavelengthTrace {
  double wavelength_nm = 0;
  FovDeg fov_deg;
  int rays = 0, rays_in_pupil = 0, rays_efficient = 0;
  double mean_efficiency = 0;
};

struct TraceResult {
  FovDeg fov_deg;
  int rays = 0, rays_in_pupil = 0, rays_efficient = 0;
  double mean_efficiency = 0;
  std::vector<TracedRay> ray_list;  // only with keep_rays
  // Additions:
  int rays_on_hoe = 0;
  double mean_efficiency_on_hoe = 0;  // mean over the rays that hit the plate (NaN with cull_to_pupil)
  double efficiency_uniformity = 0;   // 1 - std/mean of the efficiencies of the rays entering the pupil
  std::array<double, 2> gaze_deg{0, 0};
  std::vector<WavelengthTrace> per_wavelength;
  std::vector<FieldRay> field_rays;  // only with keep_field_rays: the rays that hit the plate
};

TraceResult traceScene(const Scene& scene, const TraceOptions& options);

// The two stages of traceScene(), for interactive gaze updates: the HOE part does not depend
// on the gaze, so diffractScene() once, then evaluateGaze() per gaze (pupil test + FOV only).
std::vector<TracedRay> diffractScene(const Scene& scene, const TraceOptions& options);
TraceResult evaluateGaze(const Scene& scene, std::vector<TracedRay> rays, const TraceOptions& options);

}  // namespace fovea
