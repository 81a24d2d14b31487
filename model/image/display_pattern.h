#pragma once
// Calibration patterns shown on the bench's displays (seed B.2: checkerboards for the
// geometric warps, colour patches for the colour calibration, fixation dots for the gaze
// calibration), as functions of the display pixel position, and their rendering through
// a camera's view of the display (camera pixel -> display position maps).
//
// Checkerboard: squares[0] x squares[1] squares of square_px display pixels, the outer
// top-left corner of square (0, 0) at origin_px; square (0, 0) is dark. The inner corner
// (c, r) (c < squares[0] - 1, r < squares[1] - 1) lies at origin + square_px (c + 1, r + 1).
// Square (1, 1) carries a light disc (radius 0.18 square, clear of the corners) that tells the board's
// orientation in a camera image, whatever the optics mirror or turn (orientBoardCorners()).
// Everything outside the board shows the light level (the white border detectors need).
//
// Levels are linear display radiance in 0..1. Flat patches take 8-bit style codes (0..1)
// per channel through the display gamma, seen by a monochrome camera as luminance
// (Rec. 709 weights).
//
// Rendering is anti-aliased: a camera pixel averages the pattern over its footprint on the
// display (a box of the local display-per-camera-pixel scale), exactly for the separable
// checkerboard, by coverage for the edges of discs.

#include <array>
#include <optional>

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

namespace fovea::image {

// Fields grouped by pattern kind for reading, not packed: a handful exist at a time.
struct DisplayPattern {  // NOLINT(clang-analyzer-optin.performance.Padding)
  enum class Kind { Off, Flat, Checkerboard, Dot };
  Kind kind = Kind::Off;
  // Checkerboard
  std::array<int, 2> squares{10, 7};
  double square_px = 64.0;
  Eigen::Vector2d origin_px = Eigen::Vector2d::Zero();
  bool marker = true;
  double dark = 0.05, light = 0.9;
  // Flat patch: codes 0..1 per channel (R, G, B), display gamma
  std::array<double, 3> rgb{1.0, 1.0, 1.0};
  double gamma = 2.2;
  // Dot (fixation target): light disc on a dark display
  Eigen::Vector2d dot_px = Eigen::Vector2d::Zero();
  double dot_radius_px = 8.0;

  int innerColumns() const { return squares[0] - 1; }
  int innerRows() const { return squares[1] - 1; }
  // Display position of inner corner (column, row).
  Eigen::Vector2d cornerPx(int column, int row) const;
  // Radiance averaged over the box [p - half, p + half] (display px).
  double value(const Eigen::Vector2d& p, const Eigen::Vector2d& half_footprint) const;

  bool operator==(const DisplayPattern&) const = default;
};

const char* toString(DisplayPattern::Kind k);
nlohmann::json toJson(const DisplayPattern& p);
DisplayPattern patternFromJson(const nlohmann::json& j);  // throws std::invalid_argument

DisplayPattern offPattern();
// A board of `squares` centred on the display, as large as `fill` of the display allows
// (integer square size).
DisplayPattern centredCheckerboard(std::array<int, 2> display_pixels, std::array<int, 2> squares, double fill = 0.6);
// The largest board of `squares` (integer square size) centred in rect {x0, y0, x1, y1},
// leaving `border_squares` of light border inside the rectangle on every side.
DisplayPattern checkerboardInRect(const std::array<double, 4>& rect, std::array<int, 2> squares,
                                  double border_squares = 0.5);
DisplayPattern flatPatch(std::array<double, 3> rgb);
DisplayPattern fixationDot(const Eigen::Vector2d& centre_px, double radius_px);

// Adds brightness x pattern to `radiance` (CV_32FC1 of the maps' size) at every camera pixel
// whose map entry is finite. map_x/map_y: display position seen at each camera pixel
// (CV_32FC1, NaN = nothing), brightness: relative transmission there.
void renderPattern(const DisplayPattern& pattern, const cv::Mat& map_x, const cv::Mat& map_y, const cv::Mat& brightness,
                   cv::Mat& radiance);

}  // namespace fovea::image
