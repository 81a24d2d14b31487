#include "model/image/display_pattern.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace fovea::image {

namespace {

// Integral of the square wave s(x) = +1 on [2k, 2k+1), -1 on [2k+1, 2k+2): a triangle wave.
double squareWaveIntegral(double x) {
  const double r = x - 2.0 * std::floor(0.5 * x);  // [0, 2)
  return r < 1.0 ? r : 2.0 - r;
}
// Box average of s over [x - h, x + h].
double filteredSquareWave(double x, double h) {
  if (h < 1e-6) return x - 2.0 * std::floor(0.5 * x) < 1.0 ? 1.0 : -1.0;
  return (squareWaveIntegral(x + h) - squareWaveIntegral(x - h)) / (2.0 * h);
}
// Box average of the indicator of [a, b] over [x - h, x + h].
double filteredInterval(double x, double h, double a, double b) {
  if (h < 1e-6) return x >= a && x < b ? 1.0 : 0.0;
  const double lo = std::max(a, x - h), hi = std::min(b, x + h);
  return std::max(0.0, hi - lo) / (2.0 * h);
}
// Coverage of a disc of radius R at distance d, with a linear edge of width w.
double discCoverage(double d, double R, double w) {
  if (w < 1e-6) return d <= R ? 1.0 : 0.0;
  return std::clamp(0.5 + (R - d) / w, 0.0, 1.0);
}

}  // namespace

Eigen::Vector2d DisplayPattern::cornerPx(int column, int row) const {
  return origin_px + square_px * Eigen::Vector2d(column + 1, row + 1);
}

double DisplayPattern::value(const Eigen::Vector2d& p, const Eigen::Vector2d& half) const {
  switch (kind) {
    case Kind::Off:
      return 0.0;
    case Kind::Flat: {
      auto lin = [&](double c) { return std::pow(std::clamp(c, 0.0, 1.0), gamma); };
      return 0.2126 * lin(rgb[0]) + 0.7152 * lin(rgb[1]) + 0.0722 * lin(rgb[2]);
    }
    case Kind::Dot: {
      const double w = 2.0 * std::max(half[0], half[1]);
      return light * discCoverage((p - dot_px).norm(), dot_radius_px, w);
    }
    case Kind::Checkerboard: {
      const double a = (p[0] - origin_px[0]) / square_px, b = (p[1] - origin_px[1]) / square_px;
      const double ha = half[0] / square_px, hb = half[1] / square_px;
      // Square (0,0) dark: s(a) s(b) = +1 there.
      const double sab = filteredSquareWave(a, ha) * filteredSquareWave(b, hb);
      double board = dark + (light - dark) * 0.5 * (1.0 - sab);
      if (marker && squares[0] >= 3 && squares[1] >= 3) {
        const double d = std::hypot(a - 1.5, b - 1.5);
        board += (light - board) * discCoverage(d, 0.18, 2.0 * std::max(ha, hb));
      }
      const double inside = filteredInterval(a, ha, 0.0, squares[0]) * filteredInterval(b, hb, 0.0, squares[1]);
      return inside * board + (1.0 - inside) * light;
    }
  }
  return 0.0;
}

const char* toString(DisplayPattern::Kind k) {
  switch (k) {
    case DisplayPattern::Kind::Off:
      return "off";
    case DisplayPattern::Kind::Flat:
      return "flat";
    case DisplayPattern::Kind::Checkerboard:
      return "checkerboard";
    case DisplayPattern::Kind::Dot:
      return "dot";
  }
  return "off";
}

nlohmann::json toJson(const DisplayPattern& p) {
  nlohmann::json j{{"kind", toString(p.kind)}};
  switch (p.kind) {
    case DisplayPattern::Kind::Off:
      break;
    case DisplayPattern::Kind::Flat:
      j["rgb"] = p.rgb;
      j["gamma"] = p.gamma;
      break;
    case DisplayPattern::Kind::Checkerboard:
      j["squares"] = p.squares;
      j["square_px"] = p.square_px;
      j["origin_px"] = {p.origin_px[0], p.origin_px[1]};
      j["marker"] = p.marker;
      j["dark"] = p.dark;
      j["light"] = p.light;
      break;
    case DisplayPattern::Kind::Dot:
      j["dot_px"] = {p.dot_px[0], p.dot_px[1]};
      j["dot_radius_px"] = p.dot_radius_px;
      j["light"] = p.light;
      break;
  }
  return j;
}

DisplayPattern patternFromJson(const nlohmann::json& j) {
  try {
    DisplayPattern p;
    const std::string kind = j.at("kind").get<std::string>();
    if (kind == "off") {
      p.kind = DisplayPattern::Kind::Off;
    } else if (kind == "flat") {
      p.kind = DisplayPattern::Kind::Flat;
      p.rgb = j.at("rgb").get<std::array<double, 3>>();
      p.gamma = j.value("gamma", 2.2);
    } else if (kind == "checkerboard") {
      p.kind = DisplayPattern::Kind::Checkerboard;
      p.squares = j.at("squares").get<std::array<int, 2>>();
      p.square_px = j.at("square_px").get<double>();
      const auto o = j.at("origin_px").get<std::array<double, 2>>();
      p.origin_px = {o[0], o[1]};
      p.marker = j.value("marker", true);
      p.dark = j.value("dark", p.dark);
      p.light = j.value("light", p.light);
    } else if (kind == "dot") {
      p.kind = DisplayPattern::Kind::Dot;
      const auto c = j.at("dot_px").get<std::array<double, 2>>();
      p.dot_px = {c[0], c[1]};
      p.dot_radius_px = j.at("dot_radius_px").get<double>();
      p.light = j.value("light", p.light);
    } else {
      throw std::invalid_argument("pattern kind must be off, flat, checkerboard or dot, got \"" + kind + "\"");
    }
    return p;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("pattern: ") + e.what());
  }
}

DisplayPattern offPattern() {
  return {};
}

DisplayPattern centredCheckerboard(std::array<int, 2> display_pixels, std::array<int, 2> squares, double fill) {
  DisplayPattern p;
  p.kind = DisplayPattern::Kind::Checkerboard;
  p.squares = squares;
  p.square_px =
      std::max(2.0, std::floor(std::min(fill * display_pixels[0] / squares[0], fill * display_pixels[1] / squares[1])));
  // Display pixel centres are integers: the board spans [-0.5, W - 0.5] centred.
  p.origin_px = {0.5 * (display_pixels[0] - 1) - 0.5 * squares[0] * p.square_px,
                 0.5 * (display_pixels[1] - 1) - 0.5 * squares[1] * p.square_px};
  return p;
}

DisplayPattern checkerboardInRect(const std::array<double, 4>& rect, std::array<int, 2> squares,
                                  double border_squares) {
  DisplayPattern p;
  p.kind = DisplayPattern::Kind::Checkerboard;
  p.squares = squares;
  const double w = rect[2] - rect[0], h = rect[3] - rect[1];
  p.square_px =
      std::max(2.0, std::floor(std::min(w / (squares[0] + 2 * border_squares), h / (squares[1] + 2 * border_squares))));
  p.origin_px = {0.5 * (rect[0] + rect[2]) - 0.5 * squares[0] * p.square_px,
                 0.5 * (rect[1] + rect[3]) - 0.5 * squares[1] * p.square_px};
  return p;
}

DisplayPattern flatPatch(std::array<double, 3> rgb) {
  DisplayPattern p;
  p.kind = DisplayPattern::Kind::Flat;
  p.rgb = rgb;
  return p;
}

DisplayPattern fixationDot(const Eigen::Vector2d& centre_px, double radius_px) {
  DisplayPattern p;
  p.kind = DisplayPattern::Kind::Dot;
  p.dot_px = centre_px;
  p.dot_radius_px = radius_px;
  return p;
}

void renderPattern(const DisplayPattern& pattern, const cv::Mat& map_x, const cv::Mat& map_y, const cv::Mat& brightness,
                   cv::Mat& radiance) {
  if (pattern.kind == DisplayPattern::Kind::Off) return;
  CV_Assert(map_x.type() == CV_32F && map_y.type() == CV_32F && brightness.type() == CV_32F);
  if (radiance.empty()) radiance = cv::Mat::zeros(map_x.size(), CV_32F);
  CV_Assert(radiance.size() == map_x.size() && radiance.type() == CV_32F);
  const int W = map_x.cols, H = map_x.rows;
  tbb::parallel_for(tbb::blocked_range<int>(0, H, 8), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      const float* mx = map_x.ptr<float>(y);
      const float* my = map_y.ptr<float>(y);
      const float* mb = brightness.ptr<float>(y);
      float* out = radiance.ptr<float>(y);
      const float* mx_up = map_x.ptr<float>(y > 0 ? y - 1 : std::min(y + 1, H - 1));
      const float* my_up = map_y.ptr<float>(y > 0 ? y - 1 : std::min(y + 1, H - 1));
      const float* mx_dn = map_x.ptr<float>(y + 1 < H ? y + 1 : std::max(y - 1, 0));
      const float* my_dn = map_y.ptr<float>(y + 1 < H ? y + 1 : std::max(y - 1, 0));
      for (int x = 0; x < W; ++x) {
        if (!std::isfinite(mx[x]) || mb[x] <= 0.0f) continue;
        // Display per camera pixel from the neighbours (one-sided at holes and borders).
        auto diff = [](float a, float b, float c) {
          if (std::isfinite(a) && std::isfinite(c)) return 0.5 * (c - a);
          if (std::isfinite(c)) return double(c - b);
          if (std::isfinite(a)) return double(b - a);
          return 0.0;
        };
        const int xl = x > 0 ? x - 1 : x, xr = x + 1 < W ? x + 1 : x;
        const double dxu = diff(mx[xl], mx[x], mx[xr]), dxv = diff(my[xl], my[x], my[xr]);
        const double dyu = diff(mx_up[x], mx[x], mx_dn[x]), dyv = diff(my_up[x], my[x], my_dn[x]);
        const Eigen::Vector2d half(0.5 * (std::abs(dxu) + std::abs(dyu)), 0.5 * (std::abs(dxv) + std::abs(dyv)));
        out[x] += mb[x] * static_cast<float>(pattern.value({mx[x], my[x]}, half));
      }
    }
  });
}

}  // namespace fovea::image
