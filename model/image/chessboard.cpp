#include "model/image/chessboard.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace fovea::image {

std::optional<ChessboardCorners> detectChessboard(const cv::Mat& image, int columns, int rows) {
  cv::Mat grey;
  if (image.channels() == 3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else
    grey = image;
  std::vector<cv::Point2f> corners;
  const cv::Size pattern(columns, rows);
  // Fast pass first; the exhaustive search costs seconds on a hard photo.
  bool found =
      cv::findChessboardCornersSB(grey, pattern, corners, cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_ACCURACY);
  if (!found)
    found = cv::findChessboardCornersSB(grey, pattern, corners,
                                        cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_EXHAUSTIVE | cv::CALIB_CB_ACCURACY);
  if (!found) {
    // Classic detector, refined to sub-pixel on the saddle points.
    found =
        cv::findChessboardCorners(grey, pattern, corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
    if (found)
      cv::cornerSubPix(grey, corners, cv::Size(11, 11), cv::Size(-1, -1),
                       cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 40, 0.001));
  }
  if (!found || static_cast<int>(corners.size()) != columns * rows) return std::nullopt;
  ChessboardCorners c;
  c.columns = columns;
  c.rows = rows;
  for (const auto& p : corners) c.image_px.emplace_back(p.x, p.y);
  return c;
}

}  // namespace fovea::image
