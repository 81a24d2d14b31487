#include "model/analysis/trace_evaluator.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include "model/physics/trace.h"

namespace fovea {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Unit arrival direction of a field angle (yaw = atan2(x, z), pitch = asin(y); fieldAngleDeg()).
Eigen::Vector3d fieldDirection(double yaw_deg, double pitch_deg) {
  const double y = yaw_deg * kDeg, p = pitch_deg * kDeg;
  return {std::cos(p) * std::sin(y), std::sin(p), std::cos(p) * std::cos(y)};
}

struct Span {
  double lo = 0, hi = 0;
  double width() const { return hi - lo; }
};

// Longest run of consecutive lit rays along one grid line (rays ordered by grid index; a
// ray that reaches the HOE but is dark or misses the pupil breaks the run). Returns the
// field-angle span (component k: 0 yaw, 1 pitch) of the widest run.
Span widestRun(const std::vector<const TracedRay*>& line, bool (*lit)(const TracedRay&, double), double threshold,
               int k) {
  Span best;
  bool open = false;
  Span run;
  for (const TracedRay* r : line) {
    if (r != nullptr && lit(*r, threshold)) {
      const double a = r->field_deg[k];
      if (!open) run = {a, a};
      run.lo = std::min(run.lo, a);
      run.hi = std::max(run.hi, a);
      open = true;
      if (run.width() > best.width()) best = run;
    } else {
      open = false;
    }
  }
  return best;
}

bool isLit(const TracedRay& r, double threshold) {
  return r.in_pupil && r.efficiency >= threshold;
}

}  // namespace

ContinuousFov continuousFov(const std::vector<TracedRay>& rays, double efficiency_threshold) {
  // One projector grid per wavelength: index the rays by (wavelength, column, row).
  std::map<double, std::map<std::pair<int, int>, const TracedRay*>> grids;
  for (const TracedRay& r : rays)
    if (r.hits_hoe) grids[r.wavelength_nm][{r.pixel[0], r.pixel[1]}] = &r;
  ContinuousFov out;
  bool first = true;
  for (const auto& [lambda, grid] : grids) {
    (void)lambda;
    int nx = 0, ny = 0;
    for (const auto& [ij, r] : grid) {
      (void)r;
      nx = std::max(nx, ij.first + 1);
      ny = std::max(ny, ij.second + 1);
    }
    auto at = [&](int i, int j) -> const TracedRay* {
      const auto it = grid.find({i, j});
      return it == grid.end() ? nullptr : it->second;
    };
    Span h, v;
    std::vector<const TracedRay*> line;
    for (int j = 0; j < ny; ++j) {
      line.clear();
      for (int i = 0; i < nx; ++i) line.push_back(at(i, j));
      const Span s = widestRun(line, &isLit, efficiency_threshold, 0);
      if (s.width() > h.width()) h = s;
    }
    for (int i = 0; i < nx; ++i) {
      line.clear();
      for (int j = 0; j < ny; ++j) line.push_back(at(i, j));
      const Span s = widestRun(line, &isLit, efficiency_threshold, 1);
      if (s.width() > v.width()) v = s;
    }
    const double diagonal =
        h.width() > 0 && v.width() > 0
            ? std::acos(std::clamp(fieldDirection(h.lo, v.lo).dot(fieldDirection(h.hi, v.hi)), -1.0, 1.0)) / kDeg
            : 0.0;
    // The field shown in every colour: the smallest over the wavelengths.
    if (first || h.width() < out.horizontal_deg) out.horizontal_deg = h.width();
    if (first || v.width() < out.vertical_deg) out.vertical_deg = v.width();
    if (first || diagonal < out.diagonal_deg) out.diagonal_deg = diagonal;
    first = false;
  }
  return out;
}

FovEvaluator traceEvaluator(const TraceEvaluatorOptions& options) {
  return [options](const Scene& scene, const FovQuery& q) {
    TraceOptions t;
    t.gaze_deg = q.gaze_deg;
    t.hoe_shift_mm = q.hoe_shift_mm;
    t.source_shift_mm = q.source_shift_mm;
    t.wavelength_nm = options.wavelength_nm;
    t.rays = options.rays;
    t.efficiency_threshold = options.efficiency_threshold;
    t.keep_rays = true;
    const TraceResult r = traceScene(scene, t);
    FovSample f;
    const ContinuousFov c = continuousFov(r.ray_list, options.efficiency_threshold);
    f.horizontal_deg = c.horizontal_deg;
    f.vertical_deg = c.vertical_deg;
    f.diagonal_deg = c.diagonal_deg;
    f.extent_horizontal_deg = r.fov_deg.horizontal;
    f.extent_vertical_deg = r.fov_deg.vertical;
    f.mean_efficiency = r.mean_efficiency;
    f.rays_in_pupil = r.rays_in_pupil;
    // Uniformity over the rays that reach the pupil: 1 - standard deviation / mean.
    double sum = 0, sum2 = 0;
    int n = 0;
    for (const TracedRay& ray : r.ray_list) {
      if (!ray.in_pupil) continue;
      sum += ray.efficiency;
      sum2 += ray.efficiency * ray.efficiency;
      ++n;
    }
    if (n > 0 && sum > 0) {
      const double mean = sum / n;
      const double var = std::max(0.0, sum2 / n - mean * mean);
      f.efficiency_uniformity = std::max(0.0, 1.0 - std::sqrt(var) / mean);
    }
    return f;
  };
}

}  // namespace fovea
