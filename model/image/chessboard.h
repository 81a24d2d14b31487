#pragma once
// Chessboard corner detection on real photos (seed B.2.1: grid points extracted from the
// captured checkerboard images), with OpenCV's sector-based detector, which localises the
// corners to sub-pixel accuracy itself (Duda & Frese 2018).

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace fovea::image {

struct ChessboardCorners {
  int columns = 0, rows = 0;              // inner corners
  std::vector<Eigen::Vector2d> image_px;  // row-major: index = row * columns + column
  // Ideal board position of each corner, in squares: (column, row).
  Eigen::Vector2d boardPosition(int index) const {
    const int row = index / columns, column = index % columns;
    return {double(column), double(row)};
  }
};

// `image` 8-bit grey or BGR. nullopt when the full pattern is not found.
std::optional<ChessboardCorners> detectChessboard(const cv::Mat& image, int columns, int rows);

}  // namespace fovea::image
