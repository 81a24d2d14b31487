#include "model/physics/display_camera_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "model/analysis/foveal_optics.h"
#include "model/image/warp.h"
#include "model/physics/eye_model.h"
#include "model/physics/projector_rays.h"
#include "model/physics/trace.h"
#include "model/scene/scene_geometry.h"
#include "model/units.h"

namespace fovea {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

// Catmull-Rom weights and their derivatives for nodes -1, 0, 1, 2 at parameter t.
void catmullRom(double t, double w[4], double dw[4]) {
  const double t2 = t * t, t3 = t2 * t;
  w[0] = 0.5 * (-t3 + 2 * t2 - t);
  w[1] = 0.5 * (3 * t3 - 5 * t2 + 2);
  w[2] = 0.5 * (-3 * t3 + 4 * t2 + t);
  w[3] = 0.5 * (t3 - t2);
  dw[0] = 0.5 * (-3 * t2 + 4 * t - 1);
  dw[1] = 0.5 * (9 * t2 - 10 * t);
  dw[2] = 0.5 * (-9 * t2 + 8 * t + 1);
  dw[3] = 0.5 * (3 * t2 - 2 * t);
}

std::vector<image::PointPair> thin(std::vector<image::PointPair> pairs, std::size_t max) {
  if (pairs.size() <= max) return pairs;
  std::vector<image::PointPair> out;
  const double step = static_cast<double>(pairs.size()) / static_cast<double>(max);
  for (std::size_t i = 0; i < max; ++i) out.push_back(pairs[static_cast<std::size_t>(i * step)]);
  return out;
}

// ---------------------------------------------------------------------------------------
// Peripheral display: the traced grid, interpolated.
class PeripheralMap final : public DisplayCameraMap {
 public:
  PeripheralMap(const Scene& scene, const EyeViewCamera& cam, const BenchPose& pose, const PeripheralMapOptions& o)
      : DisplayCameraMap(BenchDisplay::Peripheral, scene.projector.pixels, cam, pose) {
    TraceOptions t;
    t.hoe_shift_mm = pose.hoe_shift_mm;
    t.rays = o.rays;
    double lambda = o.wavelength_nm.value_or(0.0);
    if (!o.wavelength_nm) {
      lambda = scene.projector.wavelengths_nm.empty() ? 532.0 : scene.projector.wavelengths_nm.front();
      for (double w : scene.projector.wavelengths_nm)
        if (std::abs(w - 532.0) < std::abs(lambda - 532.0)) lambda = w;
    }
    t.wavelength_nm = lambda;
    const auto [nx, ny] = projectorGrid(scene.projector, o.rays);
    nx_ = nx;
    ny_ = ny;
    // The fringes are recorded at every plate point from the recording geometry, so a larger
    // plate only extends them: trace on one (every ray diffracted, smooth map up to the
    // projector's edges) and let the real plate's outline set the brightness, anti-aliased.
    Scene wide = scene;
    wide.hoe.size_mm = {scene.hoe.size_mm[0] + 200.0, scene.hoe.size_mm[1] + 200.0};
    const std::vector<TracedRay> rays = diffractScene(wide, t);
    const Frame nominal = frameOf(scene.hoe.pose);
    Frame plate = nominal;
    plate.origin += pose.hoe_shift_mm[0] * nominal.x() + pose.hoe_shift_mm[1] * nominal.y();
    const double half_w = 0.5 * scene.hoe.size_mm[0], half_h = 0.5 * scene.hoe.size_mm[1];
    const double edge = std::max(1e-6, o.plate_edge_mm);

    const EyeViewPlacement place = placeEyeViewCamera(scene, pose);
    EyePlacement eye = placeEye(scene, pose.camera_gaze_deg[0], pose.camera_gaze_deg[1]);
    const double R = eye.pupil_radius_mm, rim = std::max(1e-6, o.pupil_rim_mm);
    eye.pupil_radius_mm = R + 0.5 * rim;  // crossPupil then reports radii across the soft rim

    cam_.assign(static_cast<std::size_t>(nx_) * ny_, Eigen::Vector2d(kNaN, kNaN));
    valid_.assign(cam_.size(), 0);
    bright_.assign(cam_.size(), 0.0);
    std::vector<image::PointPair> inverse_pairs;
    for (const TracedRay& r : rays) {
      if (r.pixel[0] < 0 || r.pixel[0] >= nx_ || r.pixel[1] < 0 || r.pixel[1] >= ny_) continue;
      const std::size_t k = static_cast<std::size_t>(r.pixel[1]) * nx_ + r.pixel[0];
      if (!r.hits_hoe || !r.exits || !r.towards_eye) continue;
      const auto px = projectDirection(cam, place, -r.out_direction);
      if (!px) continue;
      cam_[k] = *px;
      valid_[k] = 1;
      double pupil = 0.0;
      if (r.out_direction.dot(eye.gaze) < 0.0) {
        const PupilCrossing c = crossPupil(eye, r.hoe_point, r.out_direction);
        if (c.radius_mm > 0.0 || c.in_pupil) pupil = smoothstep((R + 0.5 * rim - c.radius_mm) / rim);
      }
      const Eigen::Vector3d local = plate.toLocal(r.hoe_point);
      const double on_plate = smoothstep((half_w - std::abs(local.x())) / edge + 0.5) *
                              smoothstep((half_h - std::abs(local.y())) / edge + 0.5);
      bright_[k] = std::clamp(r.efficiency, 0.0, 1.0) * pupil * on_plate;
      // Inverse first guess from the nodes inside the camera frame and seen.
      if (bright_[k] > 0.02 && (*px)[0] >= 0 && (*px)[1] >= 0 && (*px)[0] < cam.pixels[0] && (*px)[1] < cam.pixels[1])
        inverse_pairs.push_back({*px, gridToDisplay({double(r.pixel[0]), double(r.pixel[1])})});
    }
    inverse_pairs = thin(std::move(inverse_pairs), 3000);
    if (inverse_pairs.size() >= 30) {
      try {
        guess_ = image::fitWarp(inverse_pairs, image::WarpModel::Poly3);
        has_guess_ = true;
      } catch (const image::WarpError&) {
      }
    }
  }

  std::optional<Eigen::Vector2d> toCamera(const Eigen::Vector2d& d) const override {
    Eigen::Vector2d v;
    Eigen::Matrix2d J;
    if (!evaluate(displayToGrid(d), v, &J)) return std::nullopt;
    return v;
  }

  std::optional<Eigen::Vector2d> toDisplay(const Eigen::Vector2d& c, const Eigen::Vector2d* hint) const override {
    Eigen::Vector2d start;
    if (hint && std::isfinite((*hint)[0]))
      start = *hint;
    else if (has_guess_)
      start = guess_.apply(c);
    else
      return std::nullopt;
    // Newton on grid coordinates (the interpolant's own parameters).
    Eigen::Vector2d g = displayToGrid(start);
    g[0] = std::clamp(g[0], -0.5, nx_ - 0.5);
    g[1] = std::clamp(g[1], -0.5, ny_ - 0.5);
    for (int it = 0; it < 20; ++it) {
      Eigen::Vector2d v;
      Eigen::Matrix2d J;
      if (!evaluate(g, v, &J)) return std::nullopt;
      const Eigen::Vector2d r = v - c;
      if (r.norm() < 1e-6) return gridToDisplay(g);
      if (std::abs(J.determinant()) < 1e-12) return std::nullopt;
      Eigen::Vector2d step = J.inverse() * r;
      const double n = step.norm();
      if (n > 2.0) step *= 2.0 / n;  // at most two grid cells per step
      g -= step;
      if (g[0] < -0.5 || g[1] < -0.5 || g[0] > nx_ - 0.5 || g[1] > ny_ - 0.5) return std::nullopt;
    }
    return std::nullopt;
  }

  double brightness(const Eigen::Vector2d& d) const override {
    const Eigen::Vector2d g = displayToGrid(d);
    if (g[0] < -0.5 || g[1] < -0.5 || g[0] > nx_ - 0.5 || g[1] > ny_ - 0.5) return 0.0;
    const double gx = std::clamp(g[0], 0.0, nx_ - 1.0), gy = std::clamp(g[1], 0.0, ny_ - 1.0);
    const int i = std::min(static_cast<int>(gx), nx_ - 2 < 0 ? 0 : nx_ - 2);
    const int j = std::min(static_cast<int>(gy), ny_ - 2 < 0 ? 0 : ny_ - 2);
    const double tx = gx - i, ty = gy - j;
    auto b = [&](int a, int c) {
      a = std::clamp(a, 0, nx_ - 1);
      c = std::clamp(c, 0, ny_ - 1);
      return bright_[static_cast<std::size_t>(c) * nx_ + a];
    };
    return (1 - ty) * ((1 - tx) * b(i, j) + tx * b(i + 1, j)) + ty * ((1 - tx) * b(i, j + 1) + tx * b(i + 1, j + 1));
  }

 private:
  // The tracer's grid runs along the projector's local +x, +y (projector_rays.h); display
  // pixels run the other way (column 0 on the left, row 0 at the top, seen along the beam).
  Eigen::Vector2d displayToGrid(const Eigen::Vector2d& d) const {
    return {(display_pixels_[0] - 0.5 - d[0]) * nx_ / display_pixels_[0] - 0.5,
            (display_pixels_[1] - 0.5 - d[1]) * ny_ / display_pixels_[1] - 0.5};
  }
  Eigen::Vector2d gridToDisplay(const Eigen::Vector2d& g) const {
    return {display_pixels_[0] - 0.5 - (g[0] + 0.5) * display_pixels_[0] / nx_,
            display_pixels_[1] - 0.5 - (g[1] + 0.5) * display_pixels_[1] / ny_};
  }
  // Node with linear extrapolation one node beyond the border; false when invalid.
  bool node(int i, int j, Eigen::Vector2d& out) const {
    auto raw = [&](int a, int b, Eigen::Vector2d& v) {
      const std::size_t k = static_cast<std::size_t>(b) * nx_ + a;
      if (!valid_[k]) return false;
      v = cam_[k];
      return true;
    };
    const int ci = std::clamp(i, 0, nx_ - 1), cj = std::clamp(j, 0, ny_ - 1);
    if (ci == i && cj == j) return raw(i, j, out);
    // Outside: reflect the step (2 n0 - n1) along each clamped axis.
    const int ii = ci == i ? i : (i < 0 ? 1 : nx_ - 2), jj = cj == j ? j : (j < 0 ? 1 : ny_ - 2);
    Eigen::Vector2d a, b, c, d;
    if (ci != i && cj != j) {
      if (!raw(ci, cj, a) || !raw(ii, cj, b) || !raw(ci, jj, c) || !raw(ii, jj, d)) return false;
      out = 4 * a - 2 * b - 2 * c + d;  // bilinear extrapolation of the corner
      return true;
    }
    if (!raw(ci, cj, a) || !raw(ci == i ? i : ii, cj == j ? j : jj, b)) return false;
    out = 2 * a - b;
    return true;
  }
  bool evaluate(const Eigen::Vector2d& g, Eigen::Vector2d& v, Eigen::Matrix2d* J) const {
    if (!(g[0] >= -0.5 && g[1] >= -0.5 && g[0] <= nx_ - 0.5 && g[1] <= ny_ - 0.5)) return false;
    if (nx_ < 2 || ny_ < 2) return false;
    const int i = std::clamp(static_cast<int>(std::floor(g[0])), 0, nx_ - 2);
    const int j = std::clamp(static_cast<int>(std::floor(g[1])), 0, ny_ - 2);
    double wx[4], dwx[4], wy[4], dwy[4];
    catmullRom(g[0] - i, wx, dwx);
    catmullRom(g[1] - j, wy, dwy);
    Eigen::Vector2d s = Eigen::Vector2d::Zero(), sx = s, sy = s;
    for (int b = 0; b < 4; ++b)
      for (int a = 0; a < 4; ++a) {
        Eigen::Vector2d n;
        if (!node(i - 1 + a, j - 1 + b, n)) return false;
        s += wx[a] * wy[b] * n;
        sx += dwx[a] * wy[b] * n;
        sy += wx[a] * dwy[b] * n;
      }
    v = s;
    if (J) {
      J->col(0) = sx;
      J->col(1) = sy;
    }
    return true;
  }

  int nx_ = 0, ny_ = 0;
  std::vector<Eigen::Vector2d> cam_;
  std::vector<unsigned char> valid_;
  std::vector<double> bright_;
  image::Warp2d guess_;
  bool has_guess_ = false;
};

// ---------------------------------------------------------------------------------------
// Foveal display: exact backward trace through the unfolded magnifier.
class FovealMap final : public DisplayCameraMap {
 public:
  FovealMap(const Scene& scene, const EyeViewCamera& cam, const BenchPose& pose)
      : DisplayCameraMap(BenchDisplay::Foveal, scene.foveal_display.pixels, cam, pose),
        combiner_(combinerPrescription(scene)),
        place_(placeEyeViewCamera(scene, pose)),
        origin_(placeEye(scene, 0.0, 0.0).pupil_center) {
    pitch_ = {scene.foveal_display.size_mm[0] / display_pixels_[0],
              scene.foveal_display.size_mm[1] / display_pixels_[1]};
    // First guess display -> camera from a coarse grid of backward traces.
    std::vector<image::PointPair> pairs;
    for (int j = 0; j <= 24; ++j)
      for (int i = 0; i <= 32; ++i) {
        const Eigen::Vector2d c(i * (cam.pixels[0] - 1) / 32.0, j * (cam.pixels[1] - 1) / 24.0);
        const auto d = trace(c);
        if (d && (*d)[0] > -0.1 * display_pixels_[0] && (*d)[0] < 1.1 * display_pixels_[0] &&
            (*d)[1] > -0.1 * display_pixels_[1] && (*d)[1] < 1.1 * display_pixels_[1])
          pairs.push_back({*d, c});
      }
    if (pairs.size() >= 30) {
      try {
        guess_ = image::fitWarp(pairs, image::WarpModel::Poly3);
        has_guess_ = true;
      } catch (const image::WarpError&) {
      }
    }
    if (!has_guess_) {  // the display is outside the camera's view: aim at its centre
      const Eigen::Vector3d centre_dir =
          (origin_ +
           Eigen::Vector3d(pose.foveal_shift_mm[0] * scene.foveal_display.combiner.magnification,
                           pose.foveal_shift_mm[1] * scene.foveal_display.combiner.magnification,
                           scene.foveal_display.combiner.image_distance_mm) -
           place_.pupil)
              .normalized();
      centre_px_ = projectDirection(cam, place_, centre_dir);
    }
  }

  std::optional<Eigen::Vector2d> toDisplay(const Eigen::Vector2d& c, const Eigen::Vector2d*) const override {
    auto d = trace(c);
    if (!d) return std::nullopt;
    return d;
  }

  std::optional<Eigen::Vector2d> toCamera(const Eigen::Vector2d& d) const override {
    Eigen::Vector2d start;
    if (has_guess_)
      start = guess_.apply(d);
    else if (centre_px_)
      start = *centre_px_;
    else
      return std::nullopt;
    // Newton with a central-difference Jacobian of the exact backward map.
    Eigen::Vector2d c = start;
    for (int it = 0; it < 30; ++it) {
      const auto f = trace(c);
      if (!f) return std::nullopt;
      const Eigen::Vector2d r = *f - d;
      if (r.norm() < 1e-7) return c;
      constexpr double h = 0.25;
      Eigen::Matrix2d J;
      for (int k = 0; k < 2; ++k) {
        Eigen::Vector2d e = Eigen::Vector2d::Zero();
        e[k] = h;
        const auto a = trace(c + e), b = trace(c - e);
        if (!a || !b) return std::nullopt;
        J.col(k) = (*a - *b) / (2 * h);
      }
      if (std::abs(J.determinant()) < 1e-12) return std::nullopt;
      Eigen::Vector2d step = J.inverse() * r;
      const double n = step.norm();
      if (n > 50.0) step *= 50.0 / n;
      c -= step;
    }
    return std::nullopt;
  }

  double brightness(const Eigen::Vector2d& d) const override {
    return d[0] >= -0.5 && d[1] >= -0.5 && d[0] <= display_pixels_[0] - 0.5 && d[1] <= display_pixels_[1] - 0.5 ? 1.0
                                                                                                                : 0.0;
  }

 private:
  // Camera pixel -> display pixel position (any, also outside the active area).
  std::optional<Eigen::Vector2d> trace(const Eigen::Vector2d& c) const {
    const Eigen::Vector3d dir = pixelDirection(camera_, place_, c);
    const Eigen::Vector3d p = place_.pupil - origin_;
    const auto hit = traceCombinerToDisplay(combiner_, p, p + dir);
    if (!hit) return std::nullopt;
    const double x = (*hit)[0] - pose_.foveal_shift_mm[0], y = (*hit)[1] - pose_.foveal_shift_mm[1];
    return Eigen::Vector2d(0.5 * display_pixels_[0] - 0.5 - x / pitch_[0],
                           0.5 * display_pixels_[1] - 0.5 - y / pitch_[1]);
  }

  CombinerPrescription combiner_;
  EyeViewPlacement place_;
  Eigen::Vector3d origin_;
  std::array<double, 2> pitch_{0.008, 0.008};
  image::Warp2d guess_;
  bool has_guess_ = false;
  std::optional<Eigen::Vector2d> centre_px_;
};

}  // namespace

double EyeViewCamera::focalPx() const {
  return 0.5 * pixels[0] / std::tan(0.5 * hfov_deg * kDeg);
}

const char* toString(BenchDisplay d) {
  return d == BenchDisplay::Peripheral ? "peripheral" : "foveal";
}

EyeViewPlacement placeEyeViewCamera(const Scene& scene, const BenchPose& pose) {
  const EyePlacement e = placeEye(scene, pose.camera_gaze_deg[0], pose.camera_gaze_deg[1]);
  EyeViewPlacement p;
  p.pupil = e.pupil_center;
  p.axes = rotationFromDeg({pose.camera_gaze_deg[0], pose.camera_gaze_deg[1], 0.0});
  p.pupil_radius_mm = e.pupil_radius_mm;
  return p;
}

std::optional<Eigen::Vector2d> projectDirection(const EyeViewCamera& cam, const EyeViewPlacement& place,
                                                const Eigen::Vector3d& from_dir) {
  const Eigen::Vector3d X = place.axes.transpose() * from_dir;
  if (!(X.z() > 1e-6)) return std::nullopt;
  const double x = -X.x() / X.z(), y = -X.y() / X.z();
  const double r2 = x * x + y * y;
  if (r2 > 4.0) return std::nullopt;  // beyond ~63 deg off axis: outside any lens's field
  const double k = 1.0 + cam.k1 * r2 + cam.k2 * r2 * r2;
  const double f = cam.focalPx();
  const double cx = 0.5 * (cam.pixels[0] - 1), cy = 0.5 * (cam.pixels[1] - 1);
  return Eigen::Vector2d(cx + f * x * k, cy + f * y * k);
}

Eigen::Vector3d pixelDirection(const EyeViewCamera& cam, const EyeViewPlacement& place, const Eigen::Vector2d& px) {
  const double f = cam.focalPx();
  const double cx = 0.5 * (cam.pixels[0] - 1), cy = 0.5 * (cam.pixels[1] - 1);
  const double xd = (px[0] - cx) / f, yd = (px[1] - cy) / f;
  // Undistort: solve rd = r (1 + k1 r^2 + k2 r^4) for r by Newton from r = rd.
  const double rd = std::hypot(xd, yd);
  double r = rd;
  for (int it = 0; it < 20 && rd > 0; ++it) {
    const double r2 = r * r;
    const double g = r * (1 + cam.k1 * r2 + cam.k2 * r2 * r2) - rd;
    const double dg = 1 + 3 * cam.k1 * r2 + 5 * cam.k2 * r2 * r2;
    if (std::abs(dg) < 1e-12) break;
    const double step = g / dg;
    r -= step;
    if (std::abs(step) < 1e-14) break;
  }
  const double s = rd > 0 ? r / rd : 1.0;
  return (place.axes * Eigen::Vector3d(-xd * s, -yd * s, 1.0)).normalized();
}

void DisplayCameraMap::cameraMaps(cv::Mat& map_x, cv::Mat& map_y, cv::Mat& bright) const {
  const int W = camera_.pixels[0], H = camera_.pixels[1];
  map_x.create(H, W, CV_32F);
  map_y.create(H, W, CV_32F);
  bright.create(H, W, CV_32F);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // Exact inversions on every other row and column (and the last ones); in between, bilinear
  // interpolation of those where all four are defined (the map's curvature makes that good
  // to ~1e-3 display px), exact inversion elsewhere.
  auto node = [&](int i, int n) { return std::min(2 * i, n - 1); };
  const int gw = W / 2 + 1, gh = H / 2 + 1;
  tbb::parallel_for(tbb::blocked_range<int>(0, gh, 4), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j) {
      const int y = node(j, H);
      float* mx = map_x.ptr<float>(y);
      float* my = map_y.ptr<float>(y);
      std::optional<Eigen::Vector2d> prev;
      for (int i = 0; i < gw; ++i) {
        const int x = node(i, W);
        std::optional<Eigen::Vector2d> d = toDisplay({double(x), double(y)}, prev ? &*prev : nullptr);
        if (!d && prev) d = toDisplay({double(x), double(y)}, nullptr);
        prev = d;
        mx[x] = d ? static_cast<float>((*d)[0]) : nan;
        my[x] = d ? static_cast<float>((*d)[1]) : nan;
      }
    }
  });
  tbb::parallel_for(tbb::blocked_range<int>(0, H, 8), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      const bool ynode = y % 2 == 0 || y == H - 1;
      const int y0 = ynode ? y : y - 1, y1 = ynode ? y : std::min(y + 1, H - 1);
      const double ty = y1 == y0 ? 0.0 : double(y - y0) / (y1 - y0);
      float* mx = map_x.ptr<float>(y);
      float* my = map_y.ptr<float>(y);
      float* mb = bright.ptr<float>(y);
      const float *ax = map_x.ptr<float>(y0), *ay = map_y.ptr<float>(y0);
      const float *bx = map_x.ptr<float>(y1), *by = map_y.ptr<float>(y1);
      for (int x = 0; x < W; ++x) {
        const bool xnode = x % 2 == 0 || x == W - 1;
        if (!(xnode && ynode)) {
          const int x0 = xnode ? x : x - 1, x1 = xnode ? x : std::min(x + 1, W - 1);
          const double tx = x1 == x0 ? 0.0 : double(x - x0) / (x1 - x0);
          const float v[8] = {ax[x0], ax[x1], bx[x0], bx[x1], ay[x0], ay[x1], by[x0], by[x1]};
          bool ok = true;
          for (float f : v) ok = ok && std::isfinite(f);
          if (ok) {
            mx[x] = static_cast<float>((1 - ty) * ((1 - tx) * v[0] + tx * v[1]) + ty * ((1 - tx) * v[2] + tx * v[3]));
            my[x] = static_cast<float>((1 - ty) * ((1 - tx) * v[4] + tx * v[5]) + ty * ((1 - tx) * v[6] + tx * v[7]));
          } else {
            const auto d = toDisplay({double(x), double(y)}, nullptr);
            mx[x] = d ? static_cast<float>((*d)[0]) : nan;
            my[x] = d ? static_cast<float>((*d)[1]) : nan;
          }
        }
        mb[x] = std::isfinite(mx[x]) ? static_cast<float>(brightness({mx[x], my[x]})) : 0.0f;
      }
    }
  });
}

std::unique_ptr<DisplayCameraMap> makePeripheralMap(const Scene& scene, const EyeViewCamera& camera,
                                                    const BenchPose& pose, const PeripheralMapOptions& options) {
  return std::make_unique<PeripheralMap>(scene, camera, pose, options);
}

std::unique_ptr<DisplayCameraMap> makeFovealMap(const Scene& scene, const EyeViewCamera& camera,
                                                const BenchPose& pose) {
  return std::make_unique<FovealMap>(scene, camera, pose);
}

std::unique_ptr<DisplayCameraMap> makeDisplayMap(BenchDisplay display, const Scene& scene, const EyeViewCamera& camera,
                                                 const BenchPose& pose) {
  if (display == BenchDisplay::Peripheral) return makePeripheralMap(scene, camera, pose);
  return makeFovealMap(scene, camera, pose);
}

std::array<double, 4> projectorRegionOnHoe(const Scene& scene, double aspect, double margin_mm) {
  const Projector& pr = scene.projector;
  const int nx = 161, ny = std::max(9, static_cast<int>(std::lround(161.0 * pr.pixels[1] / pr.pixels[0])));
  const Frame plate = frameOf(scene.hoe.pose);
  const Eigen::Vector3d source = plate.toLocal(projectorSource(pr, 0.0));
  const Eigen::Matrix3d axes = plate.axes.transpose() * rotationFromDeg(pr.pose.rotation_deg);
  const double th = std::tan(0.5 * pr.fov_deg[0] * kDeg), tv = std::tan(0.5 * pr.fov_deg[1] * kDeg);
  const double hw = 0.5 * scene.hoe.size_mm[0] - margin_mm, hh = 0.5 * scene.hoe.size_mm[1] - margin_mm;
  // Node (i, j) sits on projector pixel (i (W-1)/(nx-1), j (H-1)/(ny-1)).
  auto px = [&](int i, int j) {
    return Eigen::Vector2d(i * (pr.pixels[0] - 1.0) / (nx - 1), j * (pr.pixels[1] - 1.0) / (ny - 1));
  };
  std::vector<unsigned char> in(static_cast<std::size_t>(nx) * ny, 0);
  double sx = 0, sy = 0;
  int count = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector2d p = px(i, j);
      const double tx = th * (1 - (2 * p.x() + 1) / pr.pixels[0]), ty = tv * (1 - (2 * p.y() + 1) / pr.pixels[1]);
      const Eigen::Vector3d d = axes * Eigen::Vector3d(tx, ty, 1.0);
      if (d.z() == 0.0) continue;
      const double t = -source.z() / d.z();
      if (!(t > 0)) continue;
      const Eigen::Vector3d h = source + t * d;
      if (std::abs(h.x()) > hw || std::abs(h.y()) > hh) continue;
      in[static_cast<std::size_t>(j) * nx + i] = 1;
      sx += p.x();
      sy += p.y();
      ++count;
    }
  if (count == 0) return {0, 0, 0, 0};
  const Eigen::Vector2d c(sx / count, sy / count);
  auto fits = [&](double half_w) {
    const double half_h = half_w / aspect;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const Eigen::Vector2d p = px(i, j);
        if (std::abs(p.x() - c.x()) <= half_w && std::abs(p.y() - c.y()) <= half_h &&
            !in[static_cast<std::size_t>(j) * nx + i])
          return false;
      }
    return c.x() - half_w >= 0 && c.y() - half_h >= 0 && c.x() + half_w <= pr.pixels[0] - 1 &&
           c.y() + half_h <= pr.pixels[1] - 1;
  };
  double lo = 0, hi = pr.pixels[0];
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    (fits(mid) ? lo : hi) = mid;
  }
  return {c.x() - lo, c.y() - lo / aspect, c.x() + lo, c.y() + lo / aspect};
}

std::optional<Eigen::Vector2d> projectorPixelOnLineOfSight(const Scene& scene, std::array<double, 2> gaze_deg) {
  const EyePlacement e = placeEye(scene, gaze_deg[0], gaze_deg[1]);
  const Frame plate = frameOf(scene.hoe.pose);
  const double dn = e.gaze.dot(plate.z());
  if (std::abs(dn) < 1e-12) return std::nullopt;
  const double t = (plate.origin - e.pupil_center).dot(plate.z()) / dn;
  if (!(t > 0)) return std::nullopt;
  const Eigen::Vector3d X = e.pupil_center + t * e.gaze;
  const Projector& pr = scene.projector;
  const Eigen::Vector3d v = rotationFromDeg(pr.pose.rotation_deg).transpose() * (X - projectorSource(pr, 0.0));
  if (!(v.z() > 0)) return std::nullopt;
  const double th = std::tan(0.5 * pr.fov_deg[0] * kDeg), tv = std::tan(0.5 * pr.fov_deg[1] * kDeg);
  const double tx = v.x() / v.z(), ty = v.y() / v.z();
  return Eigen::Vector2d(0.5 * (pr.pixels[0] * (1 - tx / th) - 1), 0.5 * (pr.pixels[1] * (1 - ty / tv) - 1));
}

// Seed eq. S1, x_f = (b + D_e/2) tan(alpha) / M, derived rather than copied (the seed's symbols
// are not consistent between S1 and S3): the eye turns about its centre, r = D_e/2 behind the
// zero-gaze pupil; the combiner's virtual image plane lies d_f in front of that pupil, so
// d_f + r from the centre. The line of sight of gaze alpha starts at the pupil, r sin(alpha)
// off axis and r (1 - cos(alpha)) nearer the plane, and meets it at
//   x = r sin(alpha) + (d_f + r - r cos(alpha)) tan(alpha) = (d_f + r) tan(alpha)   (exact),
// the line through the eye's centre. The image moves M times the display, so x_f = x / M.
// One mapping for the follow table, the capture plans and the angular resolution
// (angular_resolution.cpp: x_c = M x_f).
std::array<double, 2> fovealShiftForGaze(const Scene& scene, std::array<double, 2> gaze_deg) {
  const auto& ic = scene.foveal_display.combiner;
  const double r = scene.eye.eyeball_diameter_mm / 2.0;
  return {(ic.image_distance_mm + r) * std::tan(gaze_deg[0] * kDeg) / ic.magnification,
          (ic.image_distance_mm + r) * std::tan(gaze_deg[1] * kDeg) / ic.magnification};
}

std::array<double, 2> fovealGazeCoverageDeg(const Scene& scene, std::array<double, 2> limits_mm) {
  const auto& ic = scene.foveal_display.combiner;
  const double lever = ic.image_distance_mm + scene.eye.eyeball_diameter_mm / 2.0;
  return {std::atan(limits_mm[0] * ic.magnification / lever) / kDeg,
          std::atan(limits_mm[1] * ic.magnification / lever) / kDeg};
}

std::array<double, 2> geometricHoeShiftForGaze(const Scene& scene, std::array<double, 2> gaze_deg) {
  const EyePlacement e0 = placeEye(scene, 0.0, 0.0), e = placeEye(scene, gaze_deg[0], gaze_deg[1]);
  const Frame hoe = frameOf(scene.hoe.pose);
  const Eigen::Vector3d d = e.pupil_center - e0.pupil_center;
  return {d.dot(hoe.x()), d.dot(hoe.y())};
}

}  // namespace fovea
