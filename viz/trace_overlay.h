#pragma once
// What the live trace draws into the 3D view (seed Fig. S5 in 3-D):
//  - ray fans projector -> HOE -> eye pupil plane, coloured by diffraction efficiency
//    (efficiency_colors.h; gray below 0.1), solid 3 px tubes when the ray enters the pupil,
//    dashed and faded when it misses it (or leaves away from the eye); a colour bar;
//  - the pupil outline (green) and the fovea on the back of the eyeball (orange, the eye's
//    fovea_radius_deg around the optical axis seen from the rotation centre);
//  - optionally the efficiency map: the plate's area lit by the projector, coloured by the
//    efficiency of the ray that lands there (mean over the shown wavelengths), drawn on
//    both faces of the plate;
//  - what the eye sees (layer "seen", shown by the eye's view only): the plate's area whose
//    rays enter the pupil, coloured by their mean efficiency, on the plate's eye side;
//  - the plate shifted by the "HOE follows gaze" travel (SceneView::setHoeDisplayShift).
// Layers: "rays", "eye_marks", "effmap", "seen". Per-wavelength toggles hide a wavelength's
// rays. The colour bar lives in the view's right margin (SceneView::legendRenderer).
//
// A binocular scene's left eye has an overlay of its own (role LeftEye): its ray fans and its
// pupil and fovea in the layers "left-rays" and "left-eye_marks", the left train's HOE shifted
// by its own x_p (SceneView::setLeftHoeDisplayShift); no colour bar (the main one's scale is
// the same), no efficiency map and no "seen" layer (the eye's view is the right eye's).

#include <array>
#include <vector>

#include <QString>

#include <Eigen/Core>

#include <vtkSmartPointer.h>

#include "model/physics/trace.h"
#include "model/scene/scene.h"

class vtkScalarBarActor;

namespace fovea::viz {

class SceneView;

enum class FanPattern { Horizontal, Vertical, Grid };

enum class OverlayRole { Main, LeftEye };

struct TraceOverlayOptions {
  bool rays = true;
  bool efficiency_map = false;
  FanPattern fan = FanPattern::Horizontal;
  int fan_rays = 25;  // rays across a fan (per wavelength)
  std::vector<double> hidden_wavelengths_nm;
  bool operator==(const TraceOverlayOptions&) const = default;
};

bool wavelengthShown(const TraceOverlayOptions& options, double wavelength_nm);

// Counts of what was drawn, for tests and the status line.
struct TraceOverlayStats {
  int rays_drawn = 0;     // rays with at least their incident segment
  int rays_in_pupil = 0;  // solid to the pupil
  int rays_missing = 0;   // dashed after the HOE
  int rays_low = 0;       // gray: efficiency below kLowEfficiency
  int effmap_cells = 0;
};

class TraceOverlay {
 public:
  explicit TraceOverlay(SceneView* view, OverlayRole role = OverlayRole::Main);
  ~TraceOverlay();
  TraceOverlay(const TraceOverlay&) = delete;
  TraceOverlay& operator=(const TraceOverlay&) = delete;

  // Rebuilds the layers from a trace of `scene` (ray_list of wavelength blocks over the
  // projector grid `grid`) with the plate shifted by hoe_shift_mm. Requests one render.
  void show(const Scene& scene, const TraceResult& trace, const std::array<int, 2>& grid,
            const std::array<double, 2>& hoe_shift_mm, const TraceOverlayOptions& options);
  void clear();
  const TraceOverlayStats& stats() const { return stats_; }
  vtkScalarBarActor* colorBar() const;
  // The view's layer this overlay draws `base` ("rays", "eye_marks", ...) into.
  QString layerName(const char* base) const;

 private:
  void setPlateShift(const Eigen::Vector3d& shift_bench);
  SceneView* view_;
  OverlayRole role_;
  vtkSmartPointer<vtkScalarBarActor> colorBar_;
  TraceOverlayStats stats_;
};

}  // namespace fovea::viz
