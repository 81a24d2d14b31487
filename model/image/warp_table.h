#pragma once
// Per-gaze warp tables (seed B.2.1, Fig. S14): for each calibrated gaze angle, the warps
// G_f (foveal display pixels <-> target), G_p (projector pixels <-> target) and H_f (target
// at the centre gaze -> target at gaze alpha), interpolated between calibrated gazes; and
// base-image generation: the image a display must show, resampled from the target with
// cv::remap through the warp.

#include <array>
#include <vector>

#include <opencv2/core.hpp>

#include "model/image/warp.h"

namespace fovea::image {

// Warps calibrated on a rectangular grid of gaze angles (yaw x pitch, degrees),
// bilinearly interpolated between them; clamped at the grid's edges.
class GazeWarpGrid {
 public:
  GazeWarpGrid() = default;
  // `warps` row-major: index = pitch_index * yaws.size() + yaw_index. Axes strictly rising.
  GazeWarpGrid(std::vector<double> yaws_deg, std::vector<double> pitches_deg, std::vector<Warp2d> warps);
  bool empty() const { return warps_.empty(); }
  // The warp at an arbitrary gaze: the bilinear blend of the four surrounding ones.
  Warp2d at(std::array<double, 2> gaze_deg) const;
  Eigen::Vector2d map(std::array<double, 2> gaze_deg, const Eigen::Vector2d& p) const { return at(gaze_deg).apply(p); }

 private:
  std::vector<double> yaws_, pitches_;
  std::vector<Warp2d> warps_;
};

struct GazeWarpTables {
  GazeWarpGrid G_f;  // foveal display pixel -> target pixel
  GazeWarpGrid G_p;  // projector pixel -> target pixel
  GazeWarpGrid H_f;  // target pixel at gaze alpha -> target pixel at the centre gaze
};

// Sampling maps for cv::remap: for each output (display) pixel (x, y), the source (target)
// position warp(x, y). CV_32FC1 maps of `size`.
void buildRemapMaps(const Warp2d& display_to_target, cv::Size size, cv::Mat& map_x, cv::Mat& map_y);
// The base image of a display: target resampled through the warp (bilinear, black outside).
cv::Mat generateBaseImage(const cv::Mat& target, const Warp2d& display_to_target, cv::Size display_size);

}  // namespace fovea::image
