#include "model/analysis/fov_edges.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace fovea {

namespace {

const std::array<double, 2>& spanAngle(const ProbeRay& r, FovAngle a) {
  return a == FovAngle::Footprint ? r.footprint_deg : r.field_deg;
}

// The angles a trace must fill: the footprint only when the spans are measured in it.
ProbeAngles anglesFor(FovAngle a) {
  return a == FovAngle::Footprint ? ProbeAngles::Both : ProbeAngles::FieldOnly;
}

struct Sample {
  double s = 0;  // coordinate along the scan line (tan)
  bool lit = false;
  double angle = 0;  // field angle along the line's axis when lit
};

struct Span {
  double lo = 0, hi = 0;
  double width() const { return hi - lo; }
};

class LineScan {
 public:
  // axis 0: the row (tan_x varies, tan_y = fixed, yaw read); 1: the column.
  LineScan(const RayProbe& probe, double lambda_nm, double threshold, FovAngle angle, int axis, double fixed,
           long long& traced)
      : probe_(probe),
        lambda_(lambda_nm),
        threshold_(threshold),
        angle_(angle),
        axis_(axis),
        fixed_(fixed),
        traced_(traced) {}

  Sample at(double s) const {
    ++traced_;
    const ProbeRay r = axis_ == 0 ? probe_.trace(s, fixed_, lambda_, anglesFor(angle_))
                                  : probe_.trace(fixed_, s, lambda_, anglesFor(angle_));
    Sample out;
    out.s = s;
    out.lit = r.in_pupil && r.efficiency >= threshold_;
    if (out.lit) out.angle = spanAngle(r, angle_)[axis_];
    return out;
  }

  // Bisects between a lit and a dark sample until the field angle of the lit end is known to
  // tol_deg (the local rate of the field angle along the line, from the lit neighbour, bounds
  // the angle between the two ends). Returns the last lit sample.
  Sample edge(Sample lit, Sample dark, const Sample& neighbour, double tol_deg) const {
    double rate =
        std::abs(lit.s - neighbour.s) > 0 ? std::abs(lit.angle - neighbour.angle) / std::abs(lit.s - neighbour.s) : 0.0;
    for (int k = 0; k < 60; ++k) {
      if (rate * std::abs(lit.s - dark.s) <= tol_deg) break;
      const Sample mid = at(0.5 * (lit.s + dark.s));
      if (mid.lit) {
        if (mid.s != lit.s) rate = std::max(rate, std::abs(mid.angle - lit.angle) / std::abs(mid.s - lit.s));
        lit = mid;
      } else {
        dark = mid;
      }
    }
    return lit;
  }

 private:
  const RayProbe& probe_;
  double lambda_, threshold_;
  FovAngle angle_;
  int axis_;
  double fixed_;
  long long& traced_;
};

// The widest lit run along one scan line through `through` (its coordinate on the line),
// in field angle along the line's axis.
Span widestRun(const LineScan& line, double from, double to, double through, const Sample& through_sample, int samples,
               double tol_deg) {
  std::vector<Sample> s;
  const int n = std::max(3, samples);
  s.reserve(n + 1);
  bool inserted = false;
  for (int i = 0; i < n; ++i) {
    const double c = i == n - 1 ? to : from + (to - from) * i / (n - 1);
    if (!inserted && through <= c) {
      if (through < c) s.push_back(through_sample);
      inserted = true;
    }
    s.push_back(c == through ? through_sample : line.at(c));
  }
  if (!inserted) s.push_back(through_sample);
  Span best;
  bool found = false;
  for (std::size_t i = 0; i < s.size();) {
    if (!s[i].lit) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < s.size() && s[j + 1].lit) ++j;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t k = i; k <= j; ++k) lo = std::min(lo, s[k].angle), hi = std::max(hi, s[k].angle);
    const Sample& in_neighbour_lo = j > i ? s[i + 1] : s[i];
    const Sample& in_neighbour_hi = j > i ? s[j - 1] : s[j];
    if (i > 0) {
      const Sample e = line.edge(s[i], s[i - 1], in_neighbour_lo, tol_deg);
      lo = std::min(lo, e.angle), hi = std::max(hi, e.angle);
    }
    if (j + 1 < s.size()) {
      const Sample e = line.edge(s[j], s[j + 1], in_neighbour_hi, tol_deg);
      lo = std::min(lo, e.angle), hi = std::max(hi, e.angle);
    }
    if (!found || hi - lo > best.width()) best = {lo, hi};
    found = true;
    i = j + 1;
  }
  return best;
}

struct Centre {
  bool found = false;
  double x = 0, y = 0;
  ProbeRay ray;
};

// Newton's method on field(tan_x, tan_y) = (0, 0) from a lit start, keeping only lit steps
// that bring the field angle closer to the centre.
Centre refineCentre(const RayProbe& probe, double lambda, double threshold, ProbeAngles angles, Centre c,
                    long long& traced) {
  const std::array<double, 2> half_tan = probe.halfTan();
  auto lit = [&](const ProbeRay& r) { return r.in_pupil && r.efficiency >= threshold; };
  const double h = 1e-5;
  for (int it = 0; it < 6; ++it) {
    const double f0 = std::hypot(c.ray.field_deg[0], c.ray.field_deg[1]);
    if (f0 < 1e-7) break;
    const ProbeRay rx = probe.trace(c.x + h, c.y, lambda, ProbeAngles::FieldOnly),
                   ry = probe.trace(c.x, c.y + h, lambda, ProbeAngles::FieldOnly);
    traced += 2;
    if (!lit(rx) || !lit(ry)) break;
    Eigen::Matrix2d J;
    J << (rx.field_deg[0] - c.ray.field_deg[0]) / h, (ry.field_deg[0] - c.ray.field_deg[0]) / h,
        (rx.field_deg[1] - c.ray.field_deg[1]) / h, (ry.field_deg[1] - c.ray.field_deg[1]) / h;
    if (!(std::abs(J.determinant()) > 0)) break;
    const Eigen::Vector2d step = J.inverse() * Eigen::Vector2d(c.ray.field_deg[0], c.ray.field_deg[1]);
    Centre next = c;
    next.x -= step.x();
    next.y -= step.y();
    if (!(std::abs(next.x) <= half_tan[0] && std::abs(next.y) <= half_tan[1])) break;  // outside the projector field
    next.ray = probe.trace(next.x, next.y, lambda, angles);
    ++traced;
    if (!lit(next.ray) || !(std::hypot(next.ray.field_deg[0], next.ray.field_deg[1]) < f0)) break;
    c = next;
  }
  return c;
}

}  // namespace

EdgeFovResult edgeFov(const RayProbe& probe, const std::vector<double>& wavelengths_nm, const EdgeFovOptions& o) {
  EdgeFovResult out;
  // Only rays inside the plate's image can be lit: the coarse grid and the scan lines cover it.
  const std::array<double, 4> box = probe.plateBoundsTan();
  const int gx = std::max(1, o.coarse_grid[0]), gy = std::max(1, o.coarse_grid[1]);
  double yaw_lo = std::numeric_limits<double>::infinity(), yaw_hi = -yaw_lo, pitch_lo = yaw_lo, pitch_hi = -yaw_lo;
  double sum = 0, sum2 = 0;
  bool first = true;
  if (!(box[1] > box[0] && box[3] > box[2])) return out;  // the plate is outside the projector field
  for (const double lambda : wavelengths_nm) {
    // 1. Coarse grid over the plate's image: statistics and the lit ray nearest the field centre.
    Centre c;
    double c_off_axis = 0;  // hypot of c's field angle, kept rather than recomputed per ray
    for (int iy = 0; iy < gy; ++iy) {
      const double y = box[2] + (box[3] - box[2]) * (iy + 0.5) / gy;
      for (int ix = 0; ix < gx; ++ix) {
        const double x = box[0] + (box[1] - box[0]) * (ix + 0.5) / gx;
        const ProbeRay r = probe.trace(x, y, lambda, anglesFor(o.angle));
        ++out.rays_traced;
        if (!r.in_pupil) continue;
        ++out.rays_in_pupil;
        sum += r.efficiency;
        sum2 += r.efficiency * r.efficiency;
        if (!(r.efficiency >= o.efficiency_threshold)) continue;
        yaw_lo = std::min(yaw_lo, r.field_deg[0]), yaw_hi = std::max(yaw_hi, r.field_deg[0]);
        pitch_lo = std::min(pitch_lo, r.field_deg[1]), pitch_hi = std::max(pitch_hi, r.field_deg[1]);
        const double off_axis = std::hypot(r.field_deg[0], r.field_deg[1]);
        if (!c.found || off_axis < c_off_axis) {
          c = {true, x, y, r};
          c_off_axis = off_axis;
        }
      }
    }
    Span h, v;
    if (c.found) {
      c = refineCentre(probe, lambda, o.efficiency_threshold, anglesFor(o.angle), c, out.rays_traced);
      const LineScan row(probe, lambda, o.efficiency_threshold, o.angle, 0, c.y, out.rays_traced);
      const LineScan column(probe, lambda, o.efficiency_threshold, o.angle, 1, c.x, out.rays_traced);
      const std::array<double, 2>& a = spanAngle(c.ray, o.angle);
      const Sample centre_row{c.x, true, a[0]}, centre_column{c.y, true, a[1]};
      if (o.scan_lines[0]) h = widestRun(row, box[0], box[1], c.x, centre_row, o.scan_samples, o.tolerance_deg);
      if (o.scan_lines[1]) v = widestRun(column, box[2], box[3], c.y, centre_column, o.scan_samples, o.tolerance_deg);
    }
    const double diagonal = h.width() > 0 && v.width() > 0 ? spanDiagonalDeg({h.lo, v.lo}, {h.hi, v.hi}) : 0.0;
    if (first || h.width() < out.fov.horizontal_deg) out.fov.horizontal_deg = h.width();
    if (first || v.width() < out.fov.vertical_deg) out.fov.vertical_deg = v.width();
    if (first || diagonal < out.fov.diagonal_deg) out.fov.diagonal_deg = diagonal;
    first = false;
  }
  if (yaw_hi >= yaw_lo) {
    out.extent.horizontal = yaw_hi - yaw_lo;
    out.extent.vertical = pitch_hi - pitch_lo;
  }
  if (out.rays_in_pupil > 0) {
    out.mean_efficiency = sum / out.rays_in_pupil;
    const double var = std::max(0.0, sum2 / out.rays_in_pupil - out.mean_efficiency * out.mean_efficiency);
    if (sum > 0) out.efficiency_uniformity = std::max(0.0, 1.0 - std::sqrt(var) / out.mean_efficiency);
  }
  return out;
}

}  // namespace fovea
