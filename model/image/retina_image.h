#pragma once
// The retinal image of both displays (issue 29): what the eye receives, in visual angle,
// linear RGB, on the target's grid (the foveated preview's angles, foveation.h: the target
// spans the projector's FOV, world-fixed; +yaw right, +pitch up, row 0 at the top).
//
// Peripheral: the projector shows the preview's peripheral image (FoveatedCompositor: the
// target at projector resolution, weighted by 1 - w_f of the B.2.3 blend) with an ideal
// geometric calibration (B.2.1), one mapping per projector pixel: each pixel shows the content
// of the world angle at which the calibration laser's ray (the laser nearest 555 nm,
// lateral_colour.h) of that pixel reaches the eye. Each laser's ray is placed where it lands
// itself, so where the layers diffract a pixel's colours apart the channels are displaced:
// per-layer lateral colour (colour fringes). With per_laser_calibration each laser's own
// landing angle picks its content (an ideal per-colour warp: no fringes). Every traced ray (trace.h, per laser) that
// enters the pupil deposits power  value x efficiency x (its cell's area in the visual field)
// at gaze + its field angle, spread evenly over its cell's parallelogram in the visual field
// (bilinear sub-splats whose weights sum to 1). Rays that miss the pupil
// deposit nothing (holes, vignetting), the efficiency map shades. The cell area is |det J| of
// the ray grid's field angles (central differences on the grid, per laser). Then each laser's
// plane is blurred by its field-dependent peripheral PSF (retinal_psf.h, peripheralSpotAt: an
// elliptical Gaussian, the HOE's astigmatism included, at the nodes of a ~10 deg grid over the
// target field, interpolated between them; a wide one on a coarser grid, see the .cpp) and
// added to its colour channel (>= 590 nm
// R, >= 490 nm G, else B; lasers sharing a channel share its value equally). Foveal: the preview's micro-OLED image
// (blend blur and weight included), pixel by pixel at gaze + its equal-angle offset (paraxial magnifier), power value x
// pixel area, blurred per channel by the foveal PSF of that primary (retinal_psf.h, its total PSF binned to canvas
// pixels).
// Units: power = sum of linear value x area in canvas pixels (a uniform white field of
// radiance 1 gives 1 per pixel). power_in_pupil is the sum of the deposited powers; every
// kernel is normalised and the canvas has a margin wider than every kernel (zero outside), so
// the canvas total (power_on_retina) equals it up to rounding. The written image is the
// canvas without its margin.
// Speckle (optional): fully developed speckle per laser, the intensity of each independent
// pattern exponential with mean 1 (Goodman, "Speckle Phenomena in Optics", ch. 3), grain one
// canvas pixel; a laser's plane is multiplied by the mean of `patterns` independent patterns
// (contrast 1/sqrt(patterns)), normalised so its power is unchanged; the image's speckle
// contrast, lasers of equal power, is 1/sqrt(patterns x lasers). With speckle_grain_pupil the
// grain is the pupil's (speckle_grain.h): each canvas pixel integrates M grains, its value
// gamma-distributed with M x patterns degrees of freedom.

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "model/analysis/retinal_psf.h"
#include "model/physics/lateral_colour.h"
#include "model/scene/scene.h"

namespace fovea::image {

struct RetinaImageOptions {
  std::array<double, 2> gaze_deg{0, 0};
  std::array<double, 2> hoe_shift_mm{0, 0};
  double accommodation_d = 1.25;
  bool blend = true;
  int speckle_patterns = 0;  // 0: no speckle
  std::uint64_t speckle_seed = 1;
  int rays = 20000;  // traced rays per laser
  // Additions:
  bool per_laser_calibration = false;  // each laser warped on its own (no lateral colour)
  // Speckle grain set by the pupil (speckle_grain.h: Airy-correlated, integrated over each
  // canvas pixel, M degrees of freedom per pattern); false: grain one canvas pixel.
  bool speckle_grain_pupil = false;
};

struct RetinaImageResult {
  cv::Mat image;   // CV_32FC3 linear RGB, the target's size
  cv::Mat canvas;  // CV_64FC3, image plus margin
  int margin_px = 0;
  double pixels_per_degree = 0;
  double power_in_pupil = 0, power_on_retina = 0;
  double power_off_canvas =
      0;  // of power_in_pupil, what edge cells would put beyond the canvas (dropped; 0 in practice)
  int rays_in_pupil = 0, rays_traced = 0;
  std::optional<double> speckle_contrast;  // measured over the lit canvas
  std::optional<double> speckle_expected;  // 1/sqrt(patterns x lasers) (grain a pixel); sqrt(sum 1/(M N))/lasers
  std::vector<double> speckle_dof;         // per laser: M of a canvas pixel (1 when the grain is a pixel)
  std::vector<PeripheralSpot> peripheral;  // per laser, at the line of sight
  std::vector<FovealSpot> foveal;          // per micro-OLED primary
  std::size_t peripheral_reference = 0, foveal_reference = 0;  // entries nearest 555 nm
  std::vector<LateralColour> lateral_colour;                   // per laser, at the line of sight
  // The field-dependent peripheral PSF: per laser (outer index), the spot at each node of the
  // grid over the target field (world yaw, pitch; deg), node index = row * columns + column.
  struct FieldSpot {
    std::array<double, 2> world_deg{0, 0};
    PeripheralSpot spot;
  };
  std::vector<FieldSpot> peripheral_field;  // lasers x nodes, laser-major
};

RetinaImageResult renderRetinaImage(const Scene& scene, const cv::Mat& target_linear_rgb,
                                    const RetinaImageOptions& options);

// Mean of `patterns` independent unit-mean exponential fields (fully developed speckle), CV_64F.
cv::Mat speckleField(cv::Size size, int patterns, std::uint64_t seed);
// std / mean over the pixels where mask (CV_8U, nonzero) is set (all pixels when empty).
double speckleContrast(const cv::Mat& field, const cv::Mat& mask = cv::Mat());

}  // namespace fovea::image
