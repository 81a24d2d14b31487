#pragma once
// Geometric calibration from checkerboard captures (seed B.2.1): the corners of a board a
// display showed, found in the camera image, give display-pixel -> camera-pixel pairs; a
// least-squares warp (warp.h) through them is the display's warp at that bench pose.
//
// Corners: chessboard.h's sector-based detector (findChessboardCornersSB) finds the board;
// cornerSubPix then refines each corner on its saddle point with a window inside one square.
//
// Orientation: the detector (chessboard.h) returns the inner corners row-major in an order
// of its own choosing; the optics may mirror the board. The board's marker disc in square
// (1, 1) (display_pattern.h) decides which of the four labellings that keep the grid's
// shape (as found, columns reversed, rows reversed, both) is the board's: the one whose
// square (1, 1) shows a disc contrasting with its own square.
//
// Scoring against a ground truth (the virtual bench): the RMS distance, in camera pixels,
// between the fitted warp and the true display -> camera map over a dense grid of display
// points inside the board's inner-corner rectangle (where the true map is defined).

#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "model/image/display_pattern.h"
#include "model/image/warp.h"

namespace fovea::image {

struct BoardObservation {
  std::vector<PointPair> pairs;  // src: display px of the inner corner, dst: camera px
  int orientation = 0;           // 0 as found, 1 columns reversed, 2 rows reversed, 3 both
  double marker_contrast = 0;    // of the chosen labelling (grey levels)
};

// nullopt when the board (all inner corners) is not found. `board` must be a checkerboard.
std::optional<BoardObservation> observeBoard(const cv::Mat& image, const DisplayPattern& board);

struct DisplayWarpFit {
  Warp2d warp;  // display px -> camera px
  WarpModel model = WarpModel::Poly3;
  double residual_px_rms = 0;  // over the corners it was fitted to
  int corners = 0;
};
DisplayWarpFit fitDisplayWarp(const BoardObservation& observation, WarpModel model = WarpModel::Poly3);

struct ErrorTally {
  double sum_sq = 0;
  int count = 0;
  double rms() const;
  void add(const ErrorTally& o) {
    sum_sq += o.sum_sq;
    count += o.count;
  }
};
// |warp(p) - truth(p)| over a samples x samples grid of display points spanning the board's
// inner corners; points where truth gives nothing are skipped.
ErrorTally compareWithTruth(const Warp2d& warp, const DisplayPattern& board,
                            const std::function<std::optional<Eigen::Vector2d>(const Eigen::Vector2d&)>& truth,
                            int samples = 25);

}  // namespace fovea::image
