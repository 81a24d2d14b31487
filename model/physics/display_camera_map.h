#pragma once
// What a camera at the eye's position sees of the two displays: the ground-truth mapping
// between display pixels and camera pixels through the simulated optics, for one bench pose
// (HOE shift, micro-OLED shift, camera gaze). The virtual bench renders its camera frames
// with it and the geometric calibration is scored against it (docs/bench-devices.md).
//
// The camera: its entrance pupil (radius = the eye pupil's) sits where the eye pupil would
// be for the camera's gaze (it turns about the eye's rotation centre, like the gaze camera
// of seed C.1), it looks along that gaze and is focused at infinity: light arriving from
// unit direction w (pointing away from the camera) lands on the pixel
//   X = R_cam^T w,  (x, y) = (-X.x / X.z, -X.y / X.z),  r^2 = x^2 + y^2,
//   u = cx + f x (1 + k1 r^2 + k2 r^4),  v = cy + f y (1 + k1 r^2 + k2 r^4)
// (a right-handed bench: with +y up and +z forward, the camera's right is bench -x; the
// wide-angle lens has the barrel distortion of k1, k2), pixel centres at integer coordinates,
// (cx, cy) the sensor centre. Camera axes R_cam = rotationFromDeg(yaw, pitch, 0).
//
// Peripheral display: projector pixel (px, py) (column 0 on the left, row 0 at the top, as
// seen looking along the beam) leaves the projector at tan-angles (projector frame)
//   tx = tan(fov_h/2) (1 - (2 px + 1) / W),  ty = tan(fov_v/2) (1 - (2 py + 1) / H)
// (the grid of projector_rays.h, read as display pixels); the real tracer (trace.h
// diffractScene, one wavelength) carries a grid of those rays through the recorded HOE stack
// with the plate shifted by the HOE stages. The fringes exist wherever the plate could be
// recorded, so the trace runs on an enlarged plate and the real plate's outline only dims
// the rays that miss it (a soft edge of plate_edge_mm). A ray is seen where its path after
// the HOE crosses the camera's pupil (soft rim); its camera pixel is that of its arrival
// direction. Between the traced rays the camera position is a bicubic (Catmull-Rom)
// interpolant of the grid, and the brightness (diffraction efficiency x pupil transmission x
// plate coverage) a bilinear one.
//
// Foveal display: the unfolded on-axis magnifier of foveal_optics.h (spherical mirror at b
// from the zero-gaze pupil, display plane at b - u). A camera pixel's ray from the camera
// pupil centre is traced backwards to the display plane (traceCombinerToDisplay); the
// display's centre sits on the axis at stage position 0 and moves with the micro-OLED stages
// (element x along bench x, y along bench y in the unfolded frame). Display columns run along
// -x and rows along -y, so the upright virtual image reads left to right in the camera.
//
// Each map answers both ways: the direction it is computed in exactly (peripheral: display ->
// camera, foveal: camera -> display) and the other by Newton's method on it (to 1e-6 px).

#include <array>
#include <memory>
#include <optional>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "model/scene/scene.h"

namespace fovea {

struct EyeViewCamera {
  std::array<int, 2> pixels{800, 600};
  double hfov_deg = 90.0;         // full horizontal field of view of the distortion-free projection
  double k1 = -0.06, k2 = 0.004;  // radial (Brown) distortion of the lens
  double focalPx() const;
};

// The bench pose the camera sees: element coordinates of the stage bindings (scene.stages).
struct BenchPose {
  std::array<double, 2> hoe_shift_mm{0.0, 0.0};     // hoe.x, hoe.y (HOE local x, y)
  std::array<double, 2> foveal_shift_mm{0.0, 0.0};  // foveal_display.x, foveal_display.y
  std::array<double, 2> camera_gaze_deg{0.0, 0.0};  // camera.yaw, camera.pitch
  bool operator==(const BenchPose&) const = default;
};

enum class BenchDisplay { Peripheral, Foveal };
const char* toString(BenchDisplay d);

// The camera's pupil centre, axes (columns: local x, y, z in bench) and pupil radius.
struct EyeViewPlacement {
  Eigen::Vector3d pupil = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  double pupil_radius_mm = 2.5;
};
EyeViewPlacement placeEyeViewCamera(const Scene& scene, const BenchPose& pose);

// Camera pixel of light arriving from `from_dir` (unit, pointing away from the camera);
// nullopt behind the camera.
std::optional<Eigen::Vector2d> projectDirection(const EyeViewCamera& cam, const EyeViewPlacement& place,
                                                const Eigen::Vector3d& from_dir);
// Unit bench direction (away from the camera) seen at a camera pixel.
Eigen::Vector3d pixelDirection(const EyeViewCamera& cam, const EyeViewPlacement& place, const Eigen::Vector2d& px);

struct PeripheralMapOptions {
  std::optional<double> wavelength_nm;  // default: the projector wavelength nearest 532 nm
  int rays = 24000;                     // traced grid (about this many rays over the projector field)
  double pupil_rim_mm = 0.3;            // width of the soft pupil edge
  double plate_edge_mm = 0.15;          // width of the soft plate edge
};

class DisplayCameraMap {
 public:
  virtual ~DisplayCameraMap() = default;
  BenchDisplay display() const { return display_; }
  std::array<int, 2> displayPixels() const { return display_pixels_; }
  const EyeViewCamera& camera() const { return camera_; }
  const BenchPose& pose() const { return pose_; }

  // Camera pixel of a display pixel position; nullopt where the optics do not map it (off
  // the plate, not diffracted, off the mirror). It may still be dark: see brightness().
  virtual std::optional<Eigen::Vector2d> toCamera(const Eigen::Vector2d& display_px) const = 0;
  // Display position seen at a camera pixel (nullopt: none). `hint`: a display position
  // close to the answer (neighbouring pixel), else a global first guess is used.
  virtual std::optional<Eigen::Vector2d> toDisplay(const Eigen::Vector2d& camera_px,
                                                   const Eigen::Vector2d* hint = nullptr) const = 0;
  // Relative brightness (0..1) with which the camera sees a display position: diffraction
  // efficiency and pupil transmission for the peripheral path, 1 for the foveal one.
  virtual double brightness(const Eigen::Vector2d& display_px) const = 0;

  // Dense camera -> display maps for rendering: CV_32FC1 display x, y (NaN where the camera
  // sees nothing of this display) and the brightness there. Parallel over rows.
  void cameraMaps(cv::Mat& map_x, cv::Mat& map_y, cv::Mat& brightness) const;

 protected:
  DisplayCameraMap(BenchDisplay d, std::array<int, 2> display_pixels, EyeViewCamera cam, BenchPose pose)
      : display_(d), display_pixels_(display_pixels), camera_(cam), pose_(pose) {}
  BenchDisplay display_;
  std::array<int, 2> display_pixels_;
  EyeViewCamera camera_;
  BenchPose pose_;
};

std::unique_ptr<DisplayCameraMap> makePeripheralMap(const Scene& scene, const EyeViewCamera& camera,
                                                    const BenchPose& pose, const PeripheralMapOptions& options = {});
std::unique_ptr<DisplayCameraMap> makeFovealMap(const Scene& scene, const EyeViewCamera& camera, const BenchPose& pose);
std::unique_ptr<DisplayCameraMap> makeDisplayMap(BenchDisplay display, const Scene& scene, const EyeViewCamera& camera,
                                                 const BenchPose& pose);

// The projector pixels that reach the HOE plate (nominal pose, plate edges pulled in by
// margin_mm so a shifted plate still covers them): the largest rectangle of the given aspect
// (width / height) around the centre of that footprint, as {x0, y0, x1, y1} in projector
// pixels. A design quantity (projector and plate geometry only), used to place the
// peripheral calibration board where the eye can see it.
std::array<double, 4> projectorRegionOnHoe(const Scene& scene, double aspect, double margin_mm = 5.0);
// The projector pixel whose ray meets the HOE plate (nominal pose) where the line of sight of
// a gaze from the pupil centre does; nullopt when the line misses the plate's plane.
std::optional<Eigen::Vector2d> projectorPixelOnLineOfSight(const Scene& scene, std::array<double, 2> gaze_deg);

// Stage targets that point the bench at a gaze (seed A.4, A.5.1): the micro-OLED shift that
// recentres the foveal image on the line of sight, x_f = (d_f + r) tan(alpha) / M per axis
// (angular_resolution.h), and the HOE shift that follows the pupil, r sin(alpha) per axis
// (the geometric x_p(alpha); the analyses' optimiseShift refines it).
std::array<double, 2> fovealShiftForGaze(const Scene& scene, std::array<double, 2> gaze_deg);
// The gaze range (deg, {lo, hi}) whose x_f stays within a micro-OLED stage's element limits
// {lo_mm, hi_mm}: the inverse of fovealShiftForGaze on one axis, atan(x_f M / (d_f + r)).
std::array<double, 2> fovealGazeCoverageDeg(const Scene& scene, std::array<double, 2> limits_mm);
std::array<double, 2> geometricHoeShiftForGaze(const Scene& scene, std::array<double, 2> gaze_deg);

}  // namespace fovea
