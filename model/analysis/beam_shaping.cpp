#include "model/analysis/beam_shaping.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>
#include <nlopt.hpp>

#include "model/physics/snell.h"
#include "model/scene/scene_geometry.h"
#include "model/units.h"

namespace fovea {

namespace {
constexpr double kFwhmPerW = 1.1774100225154747;  // sqrt(2 ln 2): FWHM / (1/e^2 radius)
constexpr double kClearApertureFraction = 0.9;
using cd = std::complex<double>;

struct BeamModel {
  double z_waist_mm, z_rayleigh_mm, lambda_eff_mm;
};

BeamModel beamModel(const Scene& scene) {
  const auto& pb = scene.projector.pixel_beam;
  const double w0 = pb.waist_fwhm_um * 1e-3 / kFwhmPerW;
  const double theta_half = pb.divergence_mrad * 1e-3 / kFwhmPerW;
  return {pb.waist_distance_mm, w0 / theta_half, std::numbers::pi * w0 * theta_half};
}

double radiusSquared(const BeamModel& m, cd q) {
  // 1/q = 1/R - i lambda/(pi w^2)  =>  w^2 = lambda / (pi * (-Im(1/q))).
  return m.lambda_eff_mm / (std::numbers::pi * -std::imag(1.0 / q));
}

Eigen::Vector3d anyPerpendicular(const Eigen::Vector3d& u) {
  return (std::abs(u.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(u).normalized();
}

struct LensGeometry {
  Eigen::Vector3d center, normal, e1, e2;
  double clear_radius_mm, focal_d_mm, index_d;
};

LensGeometry lensGeometry(const Scene& scene, const PlacedLens& pl) {
  const Frame proj = frameOf(scene.projector.pose);
  LensGeometry g;
  g.center = proj.toBench({pl.placement.decenter_mm, 0.0, pl.placement.distance_mm});
  const double t = pl.placement.tilt_deg * kDeg;
  g.normal = proj.axes * Eigen::Vector3d(std::sin(t), 0.0, std::cos(t));
  g.e2 = proj.y();
  g.e1 = g.e2.cross(g.normal).normalized();
  g.clear_radius_mm = kClearApertureFraction * pl.lens.diameter_mm / 2;
  g.focal_d_mm = pl.lens.focal_length_mm;
  g.index_d = glassIndex(pl.lens.glass, 587.6);
  return g;
}

// Real surfaces of a stock lens: vertices on the lens axis (unit `axis`, pointing away from
// the projector), signed radii (centre of curvature at vertex + R axis; 0 = plane).
struct RealLens {
  Eigen::Vector3d v1, v2, axis;
  double r1 = 0, r2 = 0, clear_radius_mm = 0;
};

}  // namespace

double biconvexRadiusMm(double focal_length_mm, double index, double center_thickness_mm) {
  const double n = index, f = focal_length_mm, t = center_thickness_mm;
  return (n - 1) * f * (1 + std::sqrt(std::max(0.0, 1 - t / (n * f))));
}

namespace {

RealLens realLens(const LensGeometry& g, const StockLens& stock) {
  RealLens l;
  l.axis = g.normal;
  l.v1 = g.center - 0.5 * stock.center_thickness_mm * g.normal;
  l.v2 = g.center + 0.5 * stock.center_thickness_mm * g.normal;
  l.clear_radius_mm = g.clear_radius_mm;
  const double n = g.index_d, f = g.focal_d_mm, t = stock.center_thickness_mm;
  if (stock.shape == "bi-convex") {
    const double r = biconvexRadiusMm(f, n, t);
    l.r1 = r;
    l.r2 = -r;
  } else {
    // Plano-convex, curved side towards the projector (the near-collimated side): the
    // effective focal length is exactly R/(n-1), whatever the thickness.
    l.r1 = (n - 1) * f;
    l.r2 = 0;
  }
  return l;
}

// Intersects and refracts at one surface; false when the ray misses or totally reflects.
bool refractAt(Eigen::Vector3d& p, Eigen::Vector3d& d, const Eigen::Vector3d& vertex, double radius,
               const Eigen::Vector3d& axis, double n_from, double n_to, double clear_radius_mm) {
  Eigen::Vector3d normal;
  if (radius == 0) {
    const double dn = d.dot(axis);
    if (std::abs(dn) < 1e-12) return false;
    p += ((vertex - p).dot(axis) / dn) * d;
    normal = axis;
  } else {
    const Eigen::Vector3d c = vertex + radius * axis;
    const Eigen::Vector3d oc = p - c;
    const double b = oc.dot(d), cc = oc.squaredNorm() - radius * radius, disc = b * b - cc;
    if (disc < 0) return false;
    const double s = std::sqrt(disc);
    // The cap next to the vertex: (x - c).axis has the sign opposite to the radius.
    const Eigen::Vector3d x1 = p + (-b - s) * d, x2 = p + (-b + s) * d;
    const bool first = ((x1 - c).dot(axis) < 0) == (radius > 0);
    p = first ? x1 : x2;
    normal = (p - c).normalized();
  }
  if (clear_radius_mm > 0) {
    const Eigen::Vector3d off = p - vertex;
    if ((off - off.dot(axis) * axis).norm() > clear_radius_mm) return false;
  }
  if (normal.dot(d) > 0) normal = -normal;
  const auto r = refractDirection(d, normal, n_from, n_to);
  if (!r) return false;
  d = r->direction.normalized();
  return true;
}

// Through both surfaces; `clear` = false skips the aperture (differential rays).
bool traceRealLens(const RealLens& l, double n_glass, Eigen::Vector3d& p, Eigen::Vector3d& d, bool clear) {
  const double ca = clear ? l.clear_radius_mm : 0.0;
  return refractAt(p, d, l.v1, l.r1, l.axis, 1.0, n_glass, ca) && refractAt(p, d, l.v2, l.r2, l.axis, n_glass, 1.0, ca);
}

struct PixelSpot {
  bool on_hoe = false, through_lens = false;
  Eigen::Vector2d hoe_local{0, 0};
  double rms_radius_mm = 0;
};

// One pixel's chief ray and Gaussian beam from the projector to the HOE plane.
PixelSpot tracePixelReal(const Scene& scene, const BeamModel& beam, const Frame& proj, const Frame& hoe,
                         const LensGeometry& lens, const StockLens& stock, double phi_h_deg, double phi_v_deg,
                         double wavelength_nm, bool& through);

PixelSpot tracePixel(const Scene& scene, const BeamModel& beam, const Frame& proj, const Frame& hoe,
                     const std::optional<LensGeometry>& lens, const std::optional<StockLens>& stock, double phi_h_deg,
                     double phi_v_deg, double wavelength_nm, bool thin_lens = true) {
  PixelSpot out;
  if (lens && !thin_lens) {
    bool through = false;
    PixelSpot real =
        tracePixelReal(scene, beam, proj, hoe, *lens, *stock, phi_h_deg, phi_v_deg, wavelength_nm, through);
    if (through) return real;  // otherwise the chief ray missed the lens: unshaped below
  }
  Eigen::Vector3d origin = proj.origin;
  Eigen::Vector3d u =
      (proj.axes * Eigen::Vector3d(std::tan(phi_h_deg * kDeg), std::tan(phi_v_deg * kDeg), 1.0)).normalized();
  cd q_t(-beam.z_waist_mm, beam.z_rayleigh_mm), q_s = q_t;
  Eigen::Vector3d axis_t = anyPerpendicular(u);

  if (lens) {
    Eigen::Vector3d n = lens->normal;
    const double un = u.dot(n);
    if (std::abs(un) > 1e-9) {
      const double t1 = (lens->center - origin).dot(n) / un;
      const Eigen::Vector3d hit = origin + t1 * u;
      const Eigen::Vector3d h3 = hit - lens->center;
      const Eigen::Vector2d h(h3.dot(lens->e1), h3.dot(lens->e2));
      if (t1 > 0 && h.norm() <= lens->clear_radius_mm) {
        out.through_lens = true;
        if (un < 0) n = -n;
        const double n_glass = glassIndex(stock->glass, wavelength_nm);
        const double f = lens->focal_d_mm * (lens->index_d - 1.0) / (n_glass - 1.0);  // chromatic focal length
        q_t += t1;
        q_s += t1;
        // Tangential plane: contains the ray and the lens normal.
        Eigen::Vector3d tang = n - n.dot(u) * u;
        tang = tang.norm() > 1e-9 ? tang.normalized() : anyPerpendicular(u);
        // Coddington oblique powers of a thin lens (Young): see header.
        const double cos_i = std::min(1.0, std::abs(u.dot(n)));
        const double sin_i = std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i));
        const double cos_r = std::sqrt(std::max(0.0, 1.0 - (sin_i / n_glass) * (sin_i / n_glass)));
        const double phi = (n_glass * cos_r - cos_i) / (n_glass - 1.0);
        const double p_s = phi / f, p_t = phi / (f * cos_i * cos_i);
        q_t = 1.0 / (1.0 / q_t - p_t);
        q_s = 1.0 / (1.0 / q_s - p_s);
        // Chief ray: paraxial slope rule relative to the lens normal, s' = s - h/f.
        const double un2 = u.dot(n);
        const Eigen::Vector2d s(u.dot(lens->e1) / un2, u.dot(lens->e2) / un2);
        const Eigen::Vector2d s2 = s - h / f;
        u = (n + s2.x() * lens->e1 + s2.y() * lens->e2).normalized();
        origin = hit;
        Eigen::Vector3d t2 = n - n.dot(u) * u;
        axis_t = t2.norm() > 1e-9 ? t2.normalized() : tang;
      }
    }
  }
  // Propagate to the HOE plane.
  const Eigen::Vector3d N = hoe.z();
  const double uN = u.dot(N);
  if (std::abs(uN) < 1e-9) return out;
  const double t = (hoe.origin - origin).dot(N) / uN;
  if (t <= 0) return out;
  const Eigen::Vector3d x = origin + t * u;
  const Eigen::Vector3d local = hoe.toLocal(x);
  out.hoe_local = {local.x(), local.y()};
  out.on_hoe = std::abs(local.x()) <= scene.hoe.size_mm[0] / 2 && std::abs(local.y()) <= scene.hoe.size_mm[1] / 2;
  q_t += t;
  q_s += t;
  const double w_t2 = radiusSquared(beam, q_t), w_s2 = radiusSquared(beam, q_s);
  const Eigen::Vector3d axis_s = u.cross(axis_t).normalized();
  // Project each cross-section axis along the ray onto the HOE plane.
  auto project = [&](const Eigen::Vector3d& a) { return Eigen::Vector3d(a - (a.dot(N) / uN) * u); };
  const Eigen::Vector3d pt = project(axis_t), ps = project(axis_s);
  out.rms_radius_mm = std::sqrt(w_t2 / 4.0 * pt.squaredNorm() + w_s2 / 4.0 * ps.squaredNorm());
  return out;
}

// Real thick lens: the chief ray is traced exactly through both surfaces; the Gaussian
// beam goes through the local first-order optics of that path, i.e. the 4x4 ray-transfer
// (Jacobian) matrix from the projector exit to the lens' exit side, found by central
// differences of real rays, applied to the complex curvature matrix:
//   Q' = (C + D Q)(A + B Q)^-1,  Q = (1/q) I at the exit,  then free space Q(L) = Q (I + L Q)^-1.
// Intensity covariance: Sigma = (1/4) (-(pi/lambda_eff) Im Q)^-1. This includes the lens'
// tilt astigmatism and its zonal (spherical) aberration at the beam's height.
PixelSpot tracePixelReal(const Scene& scene, const BeamModel& beam, const Frame& proj, const Frame& hoe,
                         const LensGeometry& lens, const StockLens& stock, double phi_h_deg, double phi_v_deg,
                         double wavelength_nm, bool& through) {
  PixelSpot out;
  through = false;
  const RealLens rl = realLens(lens, stock);
  const double n_glass = glassIndex(stock.glass, wavelength_nm);
  const Eigen::Vector3d u =
      (proj.axes * Eigen::Vector3d(std::tan(phi_h_deg * kDeg), std::tan(phi_v_deg * kDeg), 1.0)).normalized();
  const Eigen::Vector3d ea = proj.y().cross(u).normalized(), eb = u.cross(ea);
  Eigen::Vector3d p0 = proj.origin, d0 = u;
  if (!traceRealLens(rl, n_glass, p0, d0, true)) return out;
  through = true;
  out.through_lens = true;
  const Eigen::Vector3d ea2 = (ea - ea.dot(d0) * d0).normalized(), eb2 = d0.cross(ea2);
  // Output coordinates (x, y, slope x, slope y) of a perturbed input ray.
  auto outputState = [&](const Eigen::Vector4d& in, Eigen::Vector4d& state) {
    Eigen::Vector3d p = proj.origin + in[0] * ea + in[1] * eb;
    Eigen::Vector3d d = (u + in[2] * ea + in[3] * eb).normalized();
    if (!traceRealLens(rl, n_glass, p, d, false)) return false;
    const double s = (p0 - p).dot(d0) / d.dot(d0);
    const Eigen::Vector3d y = p + s * d - p0;
    state = {y.dot(ea2), y.dot(eb2), d.dot(ea2) / d.dot(d0), d.dot(eb2) / d.dot(d0)};
    return true;
  };
  Eigen::Matrix4d J;
  const double steps[4] = {1e-4, 1e-4, 1e-6, 1e-6};
  for (int k = 0; k < 4; ++k) {
    Eigen::Vector4d plus = Eigen::Vector4d::Zero(), minus = Eigen::Vector4d::Zero(), sp, sm;
    plus[k] = steps[k];
    minus[k] = -steps[k];
    if (!outputState(plus, sp) || !outputState(minus, sm)) return out;
    J.col(k) = (sp - sm) / (2 * steps[k]);
  }
  using M2 = Eigen::Matrix2cd;
  const M2 A = J.block<2, 2>(0, 0).cast<cd>(), B = J.block<2, 2>(0, 2).cast<cd>();
  const M2 C = J.block<2, 2>(2, 0).cast<cd>(), D = J.block<2, 2>(2, 2).cast<cd>();
  const cd q0(-beam.z_waist_mm, beam.z_rayleigh_mm);
  const M2 Q0 = M2::Identity() / q0;
  M2 Q = (C + D * Q0) * (A + B * Q0).inverse();
  // To the HOE plane along the chief ray.
  const Eigen::Vector3d N = hoe.z();
  const double uN = d0.dot(N);
  if (std::abs(uN) < 1e-9) return out;
  const double L = (hoe.origin - p0).dot(N) / uN;
  if (L <= 0) return out;
  Q = Q * (M2::Identity() + L * Q).inverse();
  const Eigen::Vector3d x = p0 + L * d0;
  const Eigen::Vector3d local = hoe.toLocal(x);
  out.hoe_local = {local.x(), local.y()};
  out.on_hoe = std::abs(local.x()) <= scene.hoe.size_mm[0] / 2 && std::abs(local.y()) <= scene.hoe.size_mm[1] / 2;
  Eigen::Matrix2d im = Q.imag();
  im = 0.5 * (im + im.transpose());
  const Eigen::Matrix2d sigma = 0.25 * (-(std::numbers::pi / beam.lambda_eff_mm) * im).inverse();
  Eigen::Matrix<double, 3, 2> E;
  E.col(0) = ea2;
  E.col(1) = eb2;
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d0 * N.transpose() / uN;
  const Eigen::Matrix3d foot = P * E * sigma * E.transpose() * P.transpose();
  out.rms_radius_mm = std::sqrt(std::max(0.0, foot.trace()));
  return out;
}

double distanceOutsidePolygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  bool inside = false;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Eigen::Vector2d &a = poly[j], &b = poly[i];
    if ((b.y() > p.y()) != (a.y() > p.y()) && p.x() < (a.x() - b.x()) * (p.y() - b.y()) / (a.y() - b.y()) + b.x())
      inside = !inside;
    const Eigen::Vector2d ab = a - b;
    const double tt = std::clamp((p - b).dot(ab) / std::max(1e-12, ab.squaredNorm()), 0.0, 1.0);
    best = std::min(best, (b + tt * ab - p).norm());
  }
  return inside ? 0.0 : best;
}
}  // namespace

Pose lensPose(const Scene& scene, const LensPlacement& placement) {
  const Frame proj = frameOf(scene.projector.pose);
  const Eigen::Matrix3d R =
      proj.axes * Eigen::AngleAxisd(placement.tilt_deg * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d z = R.col(2);
  const double pitch = std::asin(std::clamp(z.y(), -1.0, 1.0)) / kDeg;
  const double yaw = std::atan2(z.x(), z.z()) / kDeg;
  const Eigen::Matrix3d Rz = rotationFromDeg({yaw, pitch, 0.0}).transpose() * R;
  const double roll = std::atan2(Rz(1, 0), Rz(0, 0)) / kDeg;
  Pose p;
  p.position_mm = fromVec(proj.toBench({placement.decenter_mm, 0.0, placement.distance_mm}));
  p.rotation_deg = {yaw, pitch, roll};
  return p;
}

SpotReport evaluateSpots(const Scene& scene, const std::optional<PlacedLens>& lens, const SpotOptions& options) {
  SpotReport r;
  const BeamModel beam = beamModel(scene);
  const Frame proj = frameOf(scene.projector.pose);
  const Frame hoe = frameOf(scene.hoe.pose);
  std::optional<LensGeometry> geom;
  std::optional<StockLens> stock;
  if (lens) {
    geom = lensGeometry(scene, *lens);
    stock = lens->lens;
  }
  const double fh = scene.projector.fov_deg[0], fv = scene.projector.fov_deg[1];
  double sum2 = 0;
  for (double wl : scene.projector.wavelengths_nm) {
    for (int i = 0; i < options.grid_horizontal; ++i) {
      for (int j = 0; j < options.grid_vertical; ++j) {
        const double ph = fh * (-0.5 + (i + 0.5) / options.grid_horizontal);
        const double pv = fv * (-0.5 + (j + 0.5) / options.grid_vertical);
        const PixelSpot s = tracePixel(scene, beam, proj, hoe, geom, stock, ph, pv, wl, options.thin_lens);
        if (!s.on_hoe) continue;
        ++r.pixels_on_hoe;
        if (s.through_lens) ++r.pixels_through_lens;
        sum2 += s.rms_radius_mm * s.rms_radius_mm;
      }
    }
  }
  r.rms_spot_um =
      r.pixels_on_hoe > 0 ? 1e3 * std::sqrt(sum2 / r.pixels_on_hoe) : std::numeric_limits<double>::infinity();

  // Coverage: the projected field's border (first wavelength) must still enclose the HOE.
  const double wl0 = scene.projector.wavelengths_nm.empty() ? 532.0 : scene.projector.wavelengths_nm.front();
  std::vector<Eigen::Vector2d> border;
  constexpr int kEdge = 12;
  auto add = [&](double u, double v) {
    const PixelSpot s = tracePixel(scene, beam, proj, hoe, geom, stock, fh * u, fv * v, wl0, options.thin_lens);
    border.push_back(s.hoe_local);
  };
  for (int k = 0; k < kEdge; ++k) add(-0.5 + double(k) / kEdge, -0.5);
  for (int k = 0; k < kEdge; ++k) add(0.5, -0.5 + double(k) / kEdge);
  for (int k = 0; k < kEdge; ++k) add(0.5 - double(k) / kEdge, 0.5);
  for (int k = 0; k < kEdge; ++k) add(-0.5, 0.5 - double(k) / kEdge);
  const double hw = scene.hoe.size_mm[0] / 2, hh = scene.hoe.size_mm[1] / 2;
  for (double sx : {-1.0, 0.0, 1.0})
    for (double sy : {-1.0, 0.0, 1.0})
      if (sx != 0.0 || sy != 0.0) r.uncovered_mm += distanceOutsidePolygon(border, {sx * hw, sy * hh});
  return r;
}

namespace {
struct ObjectiveData {
  const Scene* scene;
  const StockLens* lens;
  const SpotOptions* spots;
  double uncovered_before_mm;
  int evaluations = 0;
};

double objective(unsigned n, const double* x, double* grad, void* data) {
  (void)n;
  (void)grad;  // derivative-free
  auto* d = static_cast<ObjectiveData*>(data);
  ++d->evaluations;
  const SpotReport r = evaluateSpots(*d->scene, PlacedLens{*d->lens, {x[0], x[1], x[2]}}, *d->spots);
  if (!std::isfinite(r.rms_spot_um)) return 1e9;
  // The lens must not shrink the projection off the HOE: 100 um of penalty per mm lost.
  return r.rms_spot_um + 100.0 * std::max(0.0, r.uncovered_mm - d->uncovered_before_mm);
}
}  // namespace

StudyOutcome<LensOptimization> optimizeBeamShapingLens(const Scene& scene, const std::vector<StockLens>& catalog,
                                                       const LensOptimizationOptions& options,
                                                       const StudyControl& control) {
  StudyOutcome<LensOptimization> out;
  const SpotReport before = evaluateSpots(scene, std::nullopt, options.spots);
  // Shortest chief-ray throw to the HOE plane bounds the lens distance.
  const Frame proj = frameOf(scene.projector.pose), hoe = frameOf(scene.hoe.pose);
  double min_throw = std::numeric_limits<double>::infinity();
  for (double u : {-0.5, 0.0, 0.5})
    for (double v : {-0.5, 0.0, 0.5}) {
      const Eigen::Vector3d d = (proj.axes * Eigen::Vector3d(std::tan(u * scene.projector.fov_deg[0] * kDeg),
                                                             std::tan(v * scene.projector.fov_deg[1] * kDeg), 1.0))
                                    .normalized();
      const double dn = d.dot(hoe.z());
      if (std::abs(dn) > 1e-9) {
        const double t = (hoe.origin - proj.origin).dot(hoe.z()) / dn;
        if (t > 0) min_throw = std::min(min_throw, t * d.dot(proj.z()));
      }
    }
  if (!std::isfinite(min_throw)) min_throw = 100.0;
  const double distance_bound = std::min(min_throw - 15.0, options.max_distance_mm.value_or(min_throw));

  const int starts = std::max(1, options.starts_per_lens);
  const std::size_t jobs = catalog.size() * static_cast<std::size_t>(starts);
  auto runs = runSamples<LensCandidateResult>(
      jobs,
      [&](std::size_t job) {
        const StockLens& lens = catalog[job / starts];
        const int k = static_cast<int>(job % starts);
        const double d_lo = lens.center_thickness_mm / 2 + 3.0;
        const double d_hi = std::max(d_lo + 1.0, distance_bound);
        const double dec = lens.diameter_mm / 4;
        std::vector<double> lb{d_lo, -dec, -40.0}, ub{d_hi, dec, 40.0};
        static constexpr double kTilts[] = {0.0, 15.0, -15.0, 30.0, -30.0};
        std::vector<double> x{d_lo + (k + 0.5) / starts * (d_hi - d_lo), 0.0, kTilts[k % 5]};
        ObjectiveData data{&scene, &lens, &options.spots, before.uncovered_mm};
        nlopt::opt opt(nlopt::LN_BOBYQA, 3);
        opt.set_lower_bounds(lb);
        opt.set_upper_bounds(ub);
        opt.set_min_objective(objective, &data);
        opt.set_xtol_abs(1e-4);
        opt.set_ftol_rel(1e-9);
        opt.set_maxeval(options.max_evaluations);
        opt.set_initial_step(std::vector<double>{(d_hi - d_lo) / 8, dec / 4, 5.0});
        double fmin = objective(3, x.data(), nullptr, &data);
        std::vector<double> best_x = x;
        try {
          double f = 0;
          opt.optimize(x, f);
          if (f < fmin) {
            fmin = f;
            best_x = x;
          }
        } catch (const std::exception&) {
          // Round-off limits etc.: keep the best point NLopt reached.
          // (x holds the last point; re-evaluated below like any other).
          if (objective(3, x.data(), nullptr, &data) < fmin) best_x = x;
        }
        LensCandidateResult c;
        c.lens = lens;
        c.placement = {best_x[0], best_x[1], best_x[2]};
        c.rms_spot_um = evaluateSpots(scene, PlacedLens{lens, c.placement}, options.spots).rms_spot_um;
        c.objective = objective(3, best_x.data(), nullptr, &data);
        c.evaluations = data.evaluations;
        return c;
      },
      control);
  if (!runs.ok()) return out;

  LensOptimization result;
  result.rms_before_um = before.rms_spot_um;
  for (std::size_t li = 0; li < catalog.size(); ++li) {
    const LensCandidateResult* best = nullptr;
    for (int k = 0; k < starts; ++k) {
      const auto& c = (*runs.value)[li * starts + k];
      if (!best || c.objective < best->objective) best = &c;
    }
    result.candidates.push_back(*best);
  }
  const auto best = std::min_element(result.candidates.begin(), result.candidates.end(),
                                     [](const auto& a, const auto& b) { return a.objective < b.objective; });
  result.best = {best->lens, best->placement};
  result.rms_after_um = best->rms_spot_um;
  result.pose = lensPose(scene, best->placement);
  result.improvement_percent = 100.0 * (result.rms_before_um - result.rms_after_um) / result.rms_before_um;
  result.distance_bound_mm = distance_bound;
  out.status = StudyStatus::Completed;
  out.value = std::move(result);
  return out;
}

}  // namespace fovea
