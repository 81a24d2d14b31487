#include "model/analysis/trace_evaluator.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "model/analysis/fov_edges.h"
#include "model/physics/ray_probe.h"
#include "model/physics/trace.h"
#include "model/physics/trace_pipeline.h"
#include "model/units.h"

namespace fovea {

namespace {

template <class Ray>
bool isLit(const Ray& r, double threshold) {
  return r.in_pupil && r.efficiency >= threshold;
}

struct Span {
  double lo = 0, hi = 0;
  double width() const { return hi - lo; }
};

// Longest run of consecutive lit rays along one grid line (rays ordered by grid index; a
// ray that reaches the HOE but is dark or misses the pupil breaks the run). Returns the
// field-angle span (component k: 0 yaw, 1 pitch) of the widest run.
template <class Ray>
Span widestRun(const std::vector<const Ray*>& line, double threshold, int k) {
  Span best;
  bool open = false;
  Span run;
  for (const Ray* r : line) {
    if (r != nullptr && isLit(*r, threshold)) {
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

// Rays (TracedRay or FieldRay) that hit the plate, one projector grid per wavelength.
template <class Ray>
ContinuousFov continuousFovOf(const std::vector<const Ray*>& rays, double efficiency_threshold) {
  // Index the rays by wavelength, then by (column, row) in a dense grid.
  std::vector<double> wavelengths;
  for (const Ray* r : rays)
    if (std::find(wavelengths.begin(), wavelengths.end(), r->wavelength_nm) == wavelengths.end())
      wavelengths.push_back(r->wavelength_nm);
  ContinuousFov out;
  bool first = true;
  for (const double lambda : wavelengths) {
    int nx = 0, ny = 0;
    for (const Ray* r : rays)
      if (r->wavelength_nm == lambda) {
        nx = std::max(nx, r->pixel[0] + 1);
        ny = std::max(ny, r->pixel[1] + 1);
      }
    std::vector<const Ray*> grid(static_cast<std::size_t>(nx) * ny, nullptr);  // column-major: (i, j) -> i ny + j
    for (const Ray* r : rays)
      if (r->wavelength_nm == lambda) grid[static_cast<std::size_t>(r->pixel[0]) * ny + r->pixel[1]] = r;
    auto at = [&](int i, int j) { return grid[static_cast<std::size_t>(i) * ny + j]; };
    // The row and the column through the line of sight: those of the lit ray nearest to
    // the field centre (the yaw/pitch chart stretches the yaw of rows far from pitch 0); ties
    // go to the first in (column, row) order.
    const Ray* centre = nullptr;
    for (const Ray* r : grid) {
      if (r != nullptr && isLit(*r, efficiency_threshold) &&
          (centre == nullptr ||
           std::hypot(r->field_deg[0], r->field_deg[1]) < std::hypot(centre->field_deg[0], centre->field_deg[1])))
        centre = r;
    }
    Span h, v;
    if (centre != nullptr) {
      std::vector<const Ray*> line;
      line.reserve(std::max(nx, ny));
      for (int i = 0; i < nx; ++i) line.push_back(at(i, centre->pixel[1]));
      h = widestRun(line, efficiency_threshold, 0);
      line.clear();
      for (int j = 0; j < ny; ++j) line.push_back(at(centre->pixel[0], j));
      v = widestRun(line, efficiency_threshold, 1);
    }
    const double diagonal = h.width() > 0 && v.width() > 0 ? spanDiagonalDeg({h.lo, v.lo}, {h.hi, v.hi}) : 0.0;
    // The field shown in every colour: the smallest over the wavelengths.
    if (first || h.width() < out.horizontal_deg) out.horizontal_deg = h.width();
    if (first || v.width() < out.vertical_deg) out.vertical_deg = v.width();
    if (first || diagonal < out.diagonal_deg) out.diagonal_deg = diagonal;
    first = false;
  }
  return out;
}

// The scene as the query sees it: the projector moved along its axis for an axial source shift.
const Scene& queriedScene(const Scene& scene, const FovQuery& q, std::optional<Scene>& moved) {
  if (q.source_axial_shift_mm == 0.0) return scene;
  moved = withSourceAlongAxis(scene, q.source_axial_shift_mm);
  return *moved;
}

}  // namespace

Eigen::Vector3d fieldDirection(const std::array<double, 2>& field_deg) {
  const double y = field_deg[0] * kDeg, p = field_deg[1] * kDeg;
  return {std::cos(p) * std::sin(y), std::sin(p), std::cos(p) * std::cos(y)};
}

double spanDiagonalDeg(const std::array<double, 2>& corner_a_deg, const std::array<double, 2>& corner_b_deg) {
  const double c = std::clamp(fieldDirection(corner_a_deg).dot(fieldDirection(corner_b_deg)), -1.0, 1.0);
  return std::acos(c) * 180.0 / std::numbers::pi;
}

ContinuousFov continuousFov(const std::vector<TracedRay>& rays, double efficiency_threshold) {
  std::vector<const TracedRay*> on_plate;
  for (const TracedRay& r : rays)
    if (r.hits_hoe) on_plate.push_back(&r);
  return continuousFovOf(on_plate, efficiency_threshold);
}

ContinuousFov continuousFov(const std::vector<FieldRay>& rays, double efficiency_threshold) {
  std::vector<const FieldRay*> on_plate;
  on_plate.reserve(rays.size());
  for (const FieldRay& r : rays) on_plate.push_back(&r);
  return continuousFovOf(on_plate, efficiency_threshold);
}

const char* fovMethodName(FovMethod m) {
  return m == FovMethod::Dense ? "dense" : "edges";
}

std::optional<FovMethod> parseFovMethod(const std::string& name) {
  if (name == "dense") return FovMethod::Dense;
  if (name == "edges") return FovMethod::Edges;
  return std::nullopt;
}

const char* fovDefinitionName(FovAngle a) {
  return a == FovAngle::Arrival ? "ours" : "seed";
}

std::optional<FovAngle> parseFovDefinition(const std::string& name) {
  if (name == "ours") return FovAngle::Arrival;
  if (name == "seed") return FovAngle::Footprint;
  return std::nullopt;
}

FovEvaluator traceEvaluator(const TraceEvaluatorOptions& options) {
  // One memoising pipeline per concurrent caller (the gaze studies evaluate in parallel). Only
  // rays entering the pupil matter here (FOV, efficiencies, uniformity), so the others skip the
  // coupled-wave step (cull_to_pupil: exact for everything read below).
  if (options.fov_method == FovMethod::Edges) {
    return [options](const Scene& nominal, const FovQuery& q) {
      std::optional<Scene> moved;
      const Scene& scene = queriedScene(nominal, q, moved);
      RayProbeSetup setup;
      setup.gaze_deg = q.gaze_deg;
      setup.hoe_shift_mm = q.hoe_shift_mm;
      setup.source_shift_mm = q.source_shift_mm;
      const RayProbe probe(scene, setup);
      EdgeFovOptions e;
      e.efficiency_threshold = options.efficiency_threshold;
      e.tolerance_deg = options.edge_tolerance_deg;
      e.angle = options.fov_angle;
      if (q.only_axis == 0 || q.only_axis == 1) e.scan_lines = {q.only_axis == 0, q.only_axis == 1};
      const std::vector<double> wavelengths =
          options.wavelength_nm ? std::vector<double>{*options.wavelength_nm} : scene.projector.wavelengths_nm;
      const EdgeFovResult r = edgeFov(probe, wavelengths, e);
      FovSample f;
      f.horizontal_deg = r.fov.horizontal_deg;
      f.vertical_deg = r.fov.vertical_deg;
      f.diagonal_deg = r.fov.diagonal_deg;
      f.extent_horizontal_deg = r.extent.horizontal;
      f.extent_vertical_deg = r.extent.vertical;
      f.mean_efficiency = r.mean_efficiency;
      f.rays_in_pupil = r.rays_in_pupil;
      f.efficiency_uniformity = r.efficiency_uniformity;
      return f;
    };
  }
  if (options.fov_angle != FovAngle::Arrival)
    throw std::invalid_argument("the seed's FOV definition (footprint angles) needs the edges FOV estimator");
  auto pool = std::make_shared<TracePipelinePool>();
  return [options, pool](const Scene& nominal, const FovQuery& q) {
    std::optional<Scene> moved;
    const Scene& scene = queriedScene(nominal, q, moved);
    TraceOptions t;
    t.gaze_deg = q.gaze_deg;
    t.hoe_shift_mm = q.hoe_shift_mm;
    t.source_shift_mm = q.source_shift_mm;
    t.wavelength_nm = options.wavelength_nm;
    t.rays = options.rays;
    t.efficiency_threshold = options.efficiency_threshold;
    t.keep_field_rays = true;
    t.cull_to_pupil = true;
    auto pipeline = pool->acquire();
    const TraceResult r = pipeline->run(scene, t);
    FovSample f;
    const ContinuousFov c = continuousFov(r.field_rays, options.efficiency_threshold);
    f.horizontal_deg = c.horizontal_deg;
    f.vertical_deg = c.vertical_deg;
    f.diagonal_deg = c.diagonal_deg;
    f.extent_horizontal_deg = r.fov_deg.horizontal;
    f.extent_vertical_deg = r.fov_deg.vertical;
    f.mean_efficiency = r.mean_efficiency;
    f.rays_in_pupil = r.rays_in_pupil;
    f.efficiency_uniformity = r.efficiency_uniformity;  // 1 - std/mean over the rays reaching the pupil
    return f;
  };
}

}  // namespace fovea
