#pragma once
// Spectroradiometer readings -> colour measurements (seed B.2.2: each display's primaries
// and 256 levels per channel, repeated, measured with a spectroradiometer).
//
// CSV, one reading a row, a header naming the columns (any order, extra columns ignored):
//   display,channel,level,x,y,Y,repeat
//   foveal,R,255,0.6401,0.3302,60.02,1
// or with CIE 1931 tristimulus values instead of the chromaticity (x, y absent):
//   display,channel,level,X,Y,Z,repeat
//   foveal,R,255,116.32,60.02,5.65,1
// display: foveal | peripheral; channel: R G B (or red green blue); level: integer 0..255;
// x, y: CIE 1931 chromaticity in [0, 1]; Y: luminance >= 0 (cd/m^2 or relative);
// X, Z: tristimulus values >= 0 in Y's unit (x = X / (X + Y + Z), y = Y / (X + Y + Z));
// repeat: integer >= 0 (one reading per display, channel, level and repeat).
//
// Readings are averaged per level over the repeats (the luminance curve Y[0..255]); a
// channel's primary is the mean chromaticity of its level-255 readings (with X, Y, Z: the
// chromaticity of their mean tristimulus values). Every bad row is
// reported with its line (non-numeric or out-of-range field, negative Y, wrong column
// count, duplicate reading), and so is every level without a reading; nothing is dropped
// silently, and any problem means no measurements.
#include <cstddef>
#include <string>
#include <vector>

#include "model/color/color_calibration.h"

namespace fovea::color {

struct CsvProblem {
  int line = 0;  // 1-based; 0 for problems of the whole file (missing levels)
  std::string message;
};

struct MeasurementImport {
  ColorMeasurements measurements;  // valid only when problems is empty
  std::vector<CsvProblem> problems;
  int rows = 0;                          // readings accepted
  int min_repeats = 0, max_repeats = 0;  // readings per level, over all channels
  bool tristimulus = false;              // the file gave X, Y, Z (not x, y, Y)
  bool ok() const { return problems.empty(); }
};

// The largest readings file read (256 levels x 3 channels x 2 displays x 1000 repeats is ~40 MB).
inline constexpr std::size_t kMaxMeasurementCsvBytes = std::size_t{64} << 20;

// `text` may start with a UTF-8 byte order mark. One-letter column names are case-sensitive
// (x, y chromaticity; X, Y, Z tristimulus): with x and y present the file is read as x, y, Y
// (X and Z are then extra columns); without them X, Y and Z are all needed, and a header with
// only one of X and Z is refused naming it (it is never read as x or z). A channel whose
// luminance does not rise (Y[255] <= Y[0], e.g. all zero) is a problem. At most 1000 problems
// are collected.
MeasurementImport importSpectroradiometerCsv(const std::string& text);
// "FILE:LINE: message" lines (at most `limit`, then "... and N more").
std::string formatProblems(const MeasurementImport& m, const std::string& file, std::size_t limit = 20);

}  // namespace fovea::color
