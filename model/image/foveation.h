#pragma once
// Foveated composite (seed B.2.3, Fig. S17): from a target image covering the peripheral
// field of view and a gaze, the image the micro-OLED shows (foveal), the image the laser
// projector shows (peripheral), and what the eye perceives (both mapped back to visual
// angle at the resolution each delivers, then added: the displays add light, so all of it
// runs in linear light).
//
// Angular model: the target, the projector and the foveal display map visual angle
// linearly to pixels (equal-angle sampling; paraxial, as the seed's A.5 analysis). The
// target spans the projector's FOV; the foveal display spans
// 2 atan(M w / (2 d_f)) per axis (micro-OLED width w, combiner magnification M, virtual
// image distance d_f), centred on the gaze. Eccentricity is the angular distance from the
// gaze in that (yaw, pitch) plane.
//
// Blending (B.2.3): the foveal image is blurred with a Gaussian whose sigma grows linearly
// from 0 at eps_s to sigma_match at eps_o, and the foveal/peripheral intensities cross-fade
// linearly from eps_o to eps_e. sigma_match makes the foveal image as sharp as the
// peripheral one: a display pixel of pitch p (deg) is a box of variance p^2/12, so
// sigma_match^2 = (p_p^2 - p_f^2)/12 with p = 1/(2 c) from each display's Nyquist
// resolution c (cycles per degree). Without blending: a hard switch at eps_o.

#include <array>
#include <chrono>

#include <opencv2/core.hpp>

#include "model/image/warp_table.h"
#include "model/scene/scene.h"

namespace fovea::image {

struct DisplayAngles {
  std::array<double, 2> peripheral_fov_deg{40, 22.5};
  std::array<int, 2> peripheral_px{1280, 720};
  std::array<double, 2> foveal_fov_deg{24, 13.5};
  std::array<int, 2> foveal_px{1920, 1080};
  double peripheralPpd() const { return peripheral_px[0] / peripheral_fov_deg[0]; }
  double fovealPpd() const { return foveal_px[0] / foveal_fov_deg[0]; }
  double peripheralCpd() const { return 0.5 * peripheralPpd(); }
  double fovealCpd() const { return 0.5 * fovealPpd(); }
};
DisplayAngles displayAngles(const Scene& scene);

struct BlendProfile {
  double blur_start_deg = 3, blend_start_deg = 5, blend_end_deg = 6;
  double sigma_match_deg = 0;  // blur at and beyond eps_o
  bool enabled = true;
  double fovealWeight(double eccentricity_deg) const;
  double blurSigmaDeg(double eccentricity_deg) const;
  // Radius beyond which the foveal display is dark.
  double fovealExtentDeg() const { return enabled ? blend_end_deg : blend_start_deg; }
};
// sqrt(p_p^2 - p_f^2) / sqrt(12) with p = 1/(2 c); 0 when the foveal display is the coarser.
double matchingBlurSigmaDeg(double foveal_cpd, double peripheral_cpd);
BlendProfile blendProfile(const Scene& scene, bool enabled = true);

struct CompositeTimings {
  double foveal_ms = 0, peripheral_ms = 0, perceived_ms = 0, prewarp_ms = 0, total_ms = 0;
};

// Keeps everything a gaze change does not touch (blurred copies of the target, the
// projector-resolution target, its upsampling to the perceived grid) and recomputes only
// the foveal disc and the pixels within eps_e of the old and new gazes.
class FoveatedCompositor {
 public:
  FoveatedCompositor(const Scene& scene, bool blend, GazeWarpTables warps = {});
  // Linear RGB CV_32FC3. Builds the caches (O(target) work, once per target).
  void setTarget(const cv::Mat& target_linear_rgb);
  // Updates the three images for a new gaze (yaw, pitch in degrees).
  void update(std::array<double, 2> gaze_deg);

  // What the displays show, after the geometric pre-warp (identity without calibration).
  const cv::Mat& fovealImage() const { return foveal_out_; }
  const cv::Mat& peripheralImage() const { return peripheral_out_; }
  // On the target's grid (same size and angles as the target).
  const cv::Mat& perceivedImage() const { return perceived_; }
  const cv::Mat& target() const { return target_; }
  const CompositeTimings& timings() const { return timings_; }
  const BlendProfile& profile() const { return profile_; }
  const DisplayAngles& angles() const { return angles_; }
  double targetPpd() const { return target_.cols / angles_.peripheral_fov_deg[0]; }

  // Seam visibility: mean LDR-FLIP between perceived and target over the transition
  // annulus eps_s <= eccentricity <= eps_e around the current gaze (the pixels of the
  // target grid), evaluated at the target's pixels per degree.
  struct Seam {
    double mean_flip = 0, p95_flip = 0, max_flip = 0;
    int pixels = 0;
  };
  Seam seamMetric() const;

 private:
  cv::Rect discRect(cv::Size size, std::array<double, 2> fov, std::array<double, 2> gaze, double radius_deg) const;
  void renderFoveal();
  void renderPeripheral();
  void renderPerceived();

  DisplayAngles angles_;
  BlendProfile profile_;
  GazeWarpTables warps_;
  std::array<double, 2> gaze_{0, 0};
  cv::Mat target_;
  std::vector<cv::Mat> blur_levels_;  // target blurred to k/(K-1) sigma_match
  cv::Mat peripheral_base_;           // target at projector resolution
  cv::Mat perceived_base_;            // peripheral_base_ upsampled to the target grid
  cv::Mat foveal_content_;            // blended foveal content on the target grid (disc bbox)
  cv::Mat foveal_content_buf_;        // storage behind foveal_content_
  cv::Mat scratch_;                   // both displays on the target grid, in renderPerceived
  cv::Mat foveal_ideal_, peripheral_ideal_, foveal_out_, peripheral_out_, perceived_;
  cv::Rect foveal_dirty_, peripheral_dirty_, perceived_dirty_;
  CompositeTimings timings_;
};

}  // namespace fovea::image
