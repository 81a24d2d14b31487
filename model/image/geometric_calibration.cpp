#include "model/image/geometric_calibration.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "model/image/chessboard.h"

namespace fovea::image {

namespace {

double sampleBilinear(const cv::Mat& grey, const Eigen::Vector2d& p) {
  cv::Mat patch;
  cv::getRectSubPix(grey, cv::Size(1, 1), cv::Point2f(static_cast<float>(p.x()), static_cast<float>(p.y())), patch,
                    CV_32F);
  return patch.at<float>(0, 0);
}

}  // namespace

std::optional<BoardObservation> observeBoard(const cv::Mat& image, const DisplayPattern& board) {
  if (board.kind != DisplayPattern::Kind::Checkerboard)
    throw std::invalid_argument("observeBoard: the pattern is not a checkerboard");
  const int cols = board.innerColumns(), rows = board.innerRows();
  if (cols < 2 || rows < 2) throw std::invalid_argument("observeBoard: a board needs at least 3 x 3 squares");
  auto found = detectChessboard(image, cols, rows);
  if (!found) return std::nullopt;
  cv::Mat grey;
  if (image.channels() == 3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else
    grey = image;
  // Refine on the saddle points: the sector detector's own estimate carries a bias of a few
  // tenths of a pixel under strong perspective; cornerSubPix with a window inside one square
  // brings it to a few hundredths (tests/model/tst_display_camera_map).
  std::vector<cv::Point2f> pts;
  for (const auto& p : found->image_px) pts.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
  double spacing = 1e9;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const Eigen::Vector2d p = found->image_px[r * cols + c];
      if (c + 1 < cols) spacing = std::min(spacing, (found->image_px[r * cols + c + 1] - p).norm());
      if (r + 1 < rows) spacing = std::min(spacing, (found->image_px[(r + 1) * cols + c] - p).norm());
    }
  // A detection that merged corners (spacing far below the board's) is no detection.
  std::vector<double> steps;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c + 1 < cols; ++c)
      steps.push_back((found->image_px[r * cols + c + 1] - found->image_px[r * cols + c]).norm());
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  if (spacing < 0.4 * steps[steps.size() / 2]) return std::nullopt;
  const int half = std::clamp(static_cast<int>(0.35 * spacing), 2, 7);
  cv::cornerSubPix(grey, pts, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-4));
  ChessboardCorners refined = *found;
  for (std::size_t i = 0; i < pts.size(); ++i) refined.image_px[i] = {pts[i].x, pts[i].y};
  found = refined;
  cv::Mat smooth;
  cv::GaussianBlur(grey, smooth, cv::Size(3, 3), 0.8);

  auto index = [&](int orientation, int c, int r) {
    const int cc = (orientation & 1) ? cols - 1 - c : c;
    const int rr = (orientation & 2) ? rows - 1 - r : r;
    return rr * cols + cc;
  };
  BoardObservation best;
  best.marker_contrast = -1;
  for (int o = 0; o < 4; ++o) {
    // Square (1, 1) is bounded by inner corners (0,0), (1,0), (0,1), (1,1).
    const Eigen::Vector2d a = found->image_px[index(o, 0, 0)], b = found->image_px[index(o, 1, 0)];
    const Eigen::Vector2d c = found->image_px[index(o, 0, 1)], d = found->image_px[index(o, 1, 1)];
    const Eigen::Vector2d centre = 0.25 * (a + b + c + d);
    // Square colour: halfway between the centre and each corner (outside the disc).
    double ring = 0;
    for (const Eigen::Vector2d& k : {a, b, c, d}) ring += 0.25 * sampleBilinear(smooth, centre + 0.6 * (k - centre));
    const double contrast = std::abs(sampleBilinear(smooth, centre) - ring);
    if (contrast > best.marker_contrast) {
      best.marker_contrast = contrast;
      best.orientation = o;
    }
  }
  if (!board.marker) best.orientation = 0;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      best.pairs.push_back({board.cornerPx(c, r), found->image_px[index(best.orientation, c, r)]});
  return best;
}

DisplayWarpFit fitDisplayWarp(const BoardObservation& observation, WarpModel model) {
  DisplayWarpFit f;
  f.model = model;
  f.warp = fitWarp(observation.pairs, model);
  f.residual_px_rms = rmsResidual(f.warp, observation.pairs);
  f.corners = static_cast<int>(observation.pairs.size());
  return f;
}

double ErrorTally::rms() const {
  return count > 0 ? std::sqrt(sum_sq / count) : std::nan("");
}

ErrorTally compareWithTruth(const Warp2d& warp, const DisplayPattern& board,
                            const std::function<std::optional<Eigen::Vector2d>(const Eigen::Vector2d&)>& truth,
                            int samples) {
  ErrorTally t;
  const Eigen::Vector2d lo = board.cornerPx(0, 0), hi = board.cornerPx(board.innerColumns() - 1, board.innerRows() - 1);
  const int n = std::max(2, samples);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d p = lo + Eigen::Vector2d((hi[0] - lo[0]) * i / (n - 1), (hi[1] - lo[1]) * j / (n - 1));
      const auto q = truth(p);
      if (!q) continue;
      t.sum_sq += (warp.apply(p) - *q).squaredNorm();
      ++t.count;
    }
  return t;
}

}  // namespace fovea::image
