#include "model/image/warp_table.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace fovea::image {

GazeWarpGrid::GazeWarpGrid(std::vector<double> yaws, std::vector<double> pitches, std::vector<Warp2d> warps)
    : yaws_(std::move(yaws)), pitches_(std::move(pitches)), warps_(std::move(warps)) {
  if (yaws_.empty() || pitches_.empty() || warps_.size() != yaws_.size() * pitches_.size())
    throw WarpError("gaze warp grid: need yaws x pitches warps");
  for (const auto* axis : {&yaws_, &pitches_})
    for (std::size_t i = 1; i < axis->size(); ++i)
      if (!((*axis)[i] > (*axis)[i - 1])) throw WarpError("gaze warp grid: axes must rise strictly");
}

namespace {
// Index of the cell's lower corner and the fraction within it (clamped to the axis).
std::pair<std::size_t, double> locate(const std::vector<double>& axis, double v) {
  if (axis.size() == 1 || v <= axis.front()) return {0, 0.0};
  if (v >= axis.back()) return {axis.size() - 2, 1.0};
  const std::size_t i = std::upper_bound(axis.begin(), axis.end(), v) - axis.begin() - 1;
  return {i, (v - axis[i]) / (axis[i + 1] - axis[i])};
}
}  // namespace

Warp2d GazeWarpGrid::at(std::array<double, 2> gaze) const {
  if (warps_.empty()) return Warp2d::identity();
  const auto [ix, tx] = locate(yaws_, gaze[0]);
  const auto [iy, ty] = locate(pitches_, gaze[1]);
  const std::size_t nx = yaws_.size();
  auto w = [&](std::size_t x, std::size_t y) -> const Warp2d& {
    return warps_[std::min(y, pitches_.size() - 1) * nx + std::min(x, nx - 1)];
  };
  const Warp2d lo = Warp2d::blend(w(ix, iy), w(ix + 1, iy), tx);
  const Warp2d hi = Warp2d::blend(w(ix, iy + 1), w(ix + 1, iy + 1), tx);
  return Warp2d::blend(lo, hi, ty);
}

void buildRemapMaps(const Warp2d& warp, cv::Size size, cv::Mat& map_x, cv::Mat& map_y) {
  map_x.create(size, CV_32FC1);
  map_y.create(size, CV_32FC1);
  cv::parallel_for_(cv::Range(0, size.height), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      float* mx = map_x.ptr<float>(y);
      float* my = map_y.ptr<float>(y);
      for (int x = 0; x < size.width; ++x) {
        const Eigen::Vector2d s = warp.apply({double(x), double(y)});
        mx[x] = static_cast<float>(s.x());
        my[x] = static_cast<float>(s.y());
      }
    }
  });
}

cv::Mat generateBaseImage(const cv::Mat& target, const Warp2d& warp, cv::Size display_size) {
  cv::Mat mx, my, out;
  buildRemapMaps(warp, display_size, mx, my);
  cv::remap(target, out, mx, my, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar::all(0));
  return out;
}

}  // namespace fovea::image
