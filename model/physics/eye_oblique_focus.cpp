#include "model/physics/eye_oblique_focus.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include <Eigen/Core>

#include "model/physics/schematic_eye.h"
#include "model/physics/snell.h"
#include "model/units.h"

namespace fovea {

namespace {

using P2 = Eigen::Vector2d;  // (y, z): meridional height, axial position

struct ConicSurface {
  double vertex_z, c, Q, n_before, n_after;
};

std::array<ConicSurface, 4> eyeSurfaces(const SchematicEyeState& eye) {
  const NavarroSurfaces s = navarroSurfaces(eye.lens_parameter_d);
  const double z[4] = {0.0, s.t[0], s.t[0] + s.t[1], s.t[0] + s.t[1] + s.t[2]};
  const double n[5] = {1.0, s.n[0], s.n[1], s.n[2], s.n[3]};
  std::array<ConicSurface, 4> out{};
  for (int i = 0; i < 4; ++i) out[i] = {z[i], 1.0 / s.R[i], s.Q[i], n[i], n[i + 1]};
  return out;
}

void requireField(double field_deg) {
  if (!std::isfinite(field_deg) || std::abs(field_deg) > 60.0)
    throw std::invalid_argument("eye field angle must be within -60..60 deg");
}

void requirePupilOffset(double pupil_offset_mm) {
  if (!std::isfinite(pupil_offset_mm) || std::abs(pupil_offset_mm) > kMaxPupilOffsetMm)
    throw std::invalid_argument("offset in the eye's entrance pupil must be within -4..4 mm (an 8 mm pupil)");
}

// Nearest forward intersection with the conic's branch through its vertex.
std::optional<P2> hitConic(const ConicSurface& s, const P2& p, const P2& u) {
  const double w0 = p.y() - s.vertex_z, k1 = 1.0 + s.Q;
  // c (y^2 + (1+Q) w^2) - 2 w = 0 along p + t u.
  const double a = s.c * (u.x() * u.x() + k1 * u.y() * u.y());
  const double b = 2.0 * s.c * (p.x() * u.x() + k1 * w0 * u.y()) - 2.0 * u.y();
  const double k = s.c * (p.x() * p.x() + k1 * w0 * w0) - 2.0 * w0;
  double roots[2];
  int count = 0;
  if (std::abs(a) < 1e-15) {
    if (std::abs(b) < 1e-15) return std::nullopt;
    roots[count++] = -k / b;
  } else {
    const double disc = b * b - 4.0 * a * k;
    if (disc < 0) return std::nullopt;
    const double sq = std::sqrt(disc);
    roots[count++] = (-b - sq) / (2.0 * a);
    roots[count++] = (-b + sq) / (2.0 * a);
  }
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < count; ++i) {
    const double t = roots[i];
    if (!(t > 1e-12) || t >= best) continue;
    const double y = p.x() + t * u.x(), w = w0 + t * u.y();
    const double under = 1.0 - k1 * s.c * s.c * y * y;
    if (under < 0) continue;
    const double sag = s.c * y * y / (1.0 + std::sqrt(under));
    if (std::abs(w - sag) < 1e-7) best = t;
  }
  if (!std::isfinite(best)) return std::nullopt;
  return P2(p + best * u);
}

// Refraction of direction u at a point of the conic (snell.h), with the unit normal there
// (the gradient of c (y^2 + (1+Q) w^2) - 2 w) turned to face the incoming ray.
std::optional<Refraction<P2>> refractAtConic(const ConicSurface& s, const P2& at, const P2& u) {
  P2 normal(2.0 * s.c * at.x(), 2.0 * s.c * (1.0 + s.Q) * (at.y() - s.vertex_z) - 2.0);
  normal.normalize();
  if (normal.dot(u) > 0) normal = -normal;
  return refractDirection(u, normal, s.n_before, s.n_after);
}

// Height at the stop plane (lens' front vertex) of the air ray through (h, E) along u.
std::optional<double> heightAtStop(const std::array<ConicSurface, 4>& s, double entrance_z, double h, P2 u) {
  P2 p = P2(h, entrance_z) - 30.0 * u;
  for (int i = 0; i < 2; ++i) {
    const auto hit = hitConic(s[i], p, u);
    if (!hit) return std::nullopt;
    const auto r = refractAtConic(s[i], *hit, u);
    if (!r) return std::nullopt;
    p = *hit;
    u = r->direction;
  }
  if (!(u.y() > 1e-9)) return std::nullopt;
  return p.x() + (s[2].vertex_z - p.y()) / u.y() * u.x();
}

// The real chief ray at field theta, the one through the stop centre: its height h where it
// crosses the paraxial entrance-pupil plane, by secant iteration.
std::optional<double> chiefRayHeight(const std::array<ConicSurface, 4>& s, double entrance_z, const P2& u) {
  double h0 = 0.0, h1 = 0.01;
  auto f0 = heightAtStop(s, entrance_z, h0, u), f1 = heightAtStop(s, entrance_z, h1, u);
  for (int it = 0; it < 60 && f0 && f1; ++it) {
    if (std::abs(*f1) < 1e-13) break;
    const double den = *f1 - *f0;
    if (std::abs(den) < 1e-300) return std::nullopt;
    const double h2 = h1 - *f1 * (h1 - h0) / den;
    h0 = h1;
    f0 = f1;
    h1 = h2;
    f1 = heightAtStop(s, entrance_z, h1, u);
  }
  if (!f1 || std::abs(*f1) > 1e-9) return std::nullopt;
  return h1;
}

// Ray geometry of the chief ray through the eye (independent of the pencil's vergence).
struct ChiefPath {
  double pupil_height = 0;  // where it crosses the paraxial entrance-pupil plane
  std::array<P2, 4> hit{};
  std::array<double, 4> cos_in{}, cos_out{}, k_m{}, k_s{}, along{};  // along: distance from the previous hit
  double pupil_to_first = 0;  // from the entrance-pupil crossing back to the corneal hit (> 0)
  P2 u_last;
  double retina = 0;
};

// The ray at field_deg that crosses the entrance-pupil plane offset_mm from the chief ray (0: the
// chief ray) traced through the eye to its retina; empty when it misses.
std::optional<ChiefPath> traceChiefRay(const std::array<ConicSurface, 4>& s, const SchematicEyeState& eye,
                                       double field_deg, double offset_mm) {
  const double theta = field_deg * kDeg;
  const P2 u0(std::sin(theta), std::cos(theta));
  const auto chief = chiefRayHeight(s, eye.entrance_pupil_mm, u0);
  if (!chief) return std::nullopt;
  ChiefPath path;
  path.pupil_height = *chief + offset_mm;
  const P2 pupil(path.pupil_height, eye.entrance_pupil_mm);
  P2 p = pupil - 30.0 * u0, u = u0;
  for (int i = 0; i < 4; ++i) {
    const auto hit = hitConic(s[i], p, u);
    if (!hit) return std::nullopt;
    const auto r = refractAtConic(s[i], *hit, u);
    if (!r) return std::nullopt;
    const double rr = hit->x(), q = 1.0 - s[i].Q * s[i].c * s[i].c * rr * rr;
    if (!(q > 0)) return std::nullopt;
    path.hit[i] = *hit;
    path.cos_in[i] = r->cos_in;
    path.cos_out[i] = r->cos_out;
    path.k_m[i] = s[i].c / (q * std::sqrt(q));
    path.k_s[i] = s[i].c / std::sqrt(q);
    path.along[i] = i == 0 ? 0.0 : (*hit - p).norm();
    if (i == 0) path.pupil_to_first = (pupil - *hit).dot(u0);
    p = *hit;
    u = r->direction;
  }
  // The retina: sphere of radius |R| about (0, L + R), the far intersection.
  const P2 d = p - P2(0.0, eye.axial_length_mm + kNavarroRetinaRadiusMm);
  const double b = d.dot(u), k = d.squaredNorm() - kNavarroRetinaRadiusMm * kNavarroRetinaRadiusMm;
  const double disc = b * b - k;
  if (disc < 0) return std::nullopt;
  path.retina = -b + std::sqrt(disc);
  if (!(path.retina > 0)) return std::nullopt;
  path.u_last = u;
  return path;
}

// Tangential and sagittal curvatures 1/distance after the last surface for entrance-pupil
// vergence V (1/mm).
std::array<double, 2> pencil(const std::array<ConicSurface, 4>& s, const ChiefPath& path, double v_mm) {
  const double v0 = v_mm / (1.0 + v_mm * path.pupil_to_first);  // object point 1/V from the pupil crossing
  double vt = v0, vs = v0;
  for (int i = 0; i < 4; ++i) {
    if (i > 0) {
      vt = vt / (1.0 - path.along[i] * vt);
      vs = vs / (1.0 - path.along[i] * vs);
    }
    const double n = s[i].n_before, n2 = s[i].n_after, ci = path.cos_in[i], co = path.cos_out[i];
    const double phi = n2 * co - n * ci;
    vt = (n * ci * ci * vt + phi * path.k_m[i]) / (n2 * co * co);
    vs = (n * vs + phi * path.k_s[i]) / n2;
  }
  return {vt, vs};
}

// The entrance-pupil vergence (1/mm) that puts pencil component `which` on the retina.
std::optional<double> focusedVergence(const std::array<ConicSurface, 4>& s, const ChiefPath& path, int which,
                                      double start_mm) {
  const double target = 1.0 / path.retina;
  auto g = [&](double v) { return pencil(s, path, v)[which] - target; };
  double v0 = start_mm, v1 = start_mm + 1e-3, g0 = g(v0), g1 = g(v1);
  for (int it = 0; it < 80; ++it) {
    if (std::abs(g1) < 1e-15) return v1;
    const double den = g1 - g0;
    if (std::abs(den) < 1e-300) break;
    const double v2 = v1 - g1 * (v1 - v0) / den;
    v0 = v1;
    g0 = g1;
    v1 = v2;
    g1 = g(v1);
  }
  if (std::abs(g1) < 1e-12) return v1;
  return std::nullopt;
}

// The entrance-pupil vergences (D) that focus the tangential and the sagittal pencil of the ray
// at theta_deg (>= 0) crossing the pupil plane offset_mm from the chief ray on the retina.
std::optional<std::array<double, 2>> focusedPencils(const std::array<ConicSurface, 4>& s, const SchematicEyeState& eye,
                                                    double theta_deg, double offset_mm) {
  const auto path = traceChiefRay(s, eye, theta_deg, offset_mm);
  if (!path) return std::nullopt;
  const double start = -eye.accommodation_d / 1000.0;
  const auto t = focusedVergence(s, *path, 0, start), v = focusedVergence(s, *path, 1, start);
  if (!t || !v) return std::nullopt;
  return std::array<double, 2>{*t * 1000.0, *v * 1000.0};
}

}  // namespace

ChiefRayFoci navarroChiefRayFoci(const SchematicEyeState& eye, double field_deg, double vergence_d,
                                 double pupil_offset_mm) {
  requireField(field_deg);
  requirePupilOffset(pupil_offset_mm);
  const auto surfaces = eyeSurfaces(eye);
  ChiefRayFoci f;
  const auto path = traceChiefRay(surfaces, eye, field_deg, pupil_offset_mm);
  if (!path) return f;
  const auto v = pencil(surfaces, *path, vergence_d / 1000.0);
  f.valid = true;
  f.pupil_height_mm = path->pupil_height;
  f.last_hit_y_mm = path->hit[3].x();
  f.last_hit_z_mm = path->hit[3].y();
  f.direction_y = path->u_last.x();
  f.direction_z = path->u_last.y();
  f.tangential_mm = v[0] == 0 ? std::numeric_limits<double>::infinity() : 1.0 / v[0];
  f.sagittal_mm = v[1] == 0 ? std::numeric_limits<double>::infinity() : 1.0 / v[1];
  f.retina_mm = path->retina;
  return f;
}

EyeObliqueFocus eyeObliqueFocus(const SchematicEyeState& eye, double field_deg, double pupil_offset_mm) {
  requireField(field_deg);
  requirePupilOffset(pupil_offset_mm);
  const auto surfaces = eyeSurfaces(eye);
  EyeObliqueFocus out;
  out.field_deg = field_deg;
  out.pupil_offset_mm = pupil_offset_mm;
  // A negative field mirrors the meridional plane: the offset changes sign with it.
  const double sign = field_deg < 0 ? -1.0 : 1.0;
  const auto axis = focusedPencils(surfaces, eye, 0.0, 0.0);
  const auto at = focusedPencils(surfaces, eye, std::abs(field_deg), sign * pupil_offset_mm);
  if (!axis || !at) return out;
  out.axis_d = (*axis)[0];
  out.tangential_d = (*at)[0];
  out.sagittal_d = (*at)[1];
  out.power_tangential_d = out.axis_d - out.tangential_d;
  out.power_sagittal_d = out.axis_d - out.sagittal_d;
  out.astigmatism_d = std::abs(out.power_tangential_d - out.power_sagittal_d);
  out.valid = true;
  return out;
}

EyePencilPower eyePencilPower(const SchematicEyeState& eye, double field_deg, double offset_meridional_mm,
                              double offset_sagittal_mm) {
  requireField(field_deg);
  const double rho = std::hypot(offset_meridional_mm, offset_sagittal_mm);
  requirePupilOffset(rho);
  // One set of surfaces and one axis for the three pencils (chief ray, +|h|, -|h|); powers are
  // V_axis - V, as eyeObliqueFocus gives them.
  const auto surfaces = eyeSurfaces(eye);
  const double theta = std::abs(field_deg), sign = field_deg < 0 ? -1.0 : 1.0;
  EyePencilPower out;
  const auto axis = focusedPencils(surfaces, eye, 0.0, 0.0), chief = focusedPencils(surfaces, eye, theta, 0.0);
  if (!axis || !chief) return out;
  const double v_axis = (*axis)[0];
  out.meridional_d = v_axis - (*chief)[0];
  out.sagittal_d = v_axis - (*chief)[1];
  if (rho > 0) {
    const auto plus = focusedPencils(surfaces, eye, theta, sign * rho);
    const auto minus = focusedPencils(surfaces, eye, theta, -sign * rho);
    if (!plus || !minus) return out;
    // Powers differ from vergences by the sign and v_axis, which the even part's difference and
    // the odd part cancel.
    const double even_t = (*chief)[0] - 0.5 * ((*plus)[0] + (*minus)[0]);
    const double even_s = (*chief)[1] - 0.5 * ((*plus)[1] + (*minus)[1]);
    const double odd_t = -0.5 * ((*plus)[0] - (*minus)[0]);
    const double odd_s = -0.5 * ((*plus)[1] - (*minus)[1]);
    const double c = offset_meridional_mm / rho, sn = offset_sagittal_mm / rho;
    out.meridional_d += even_t * c * c + even_s * sn * sn + odd_t * c;
    out.sagittal_d += even_s * c * c + even_t * sn * sn + odd_s * c;
    out.cross_d = (even_t - even_s) * c * sn + odd_s * sn;
  }
  out.valid = true;
  return out;
}

}  // namespace fovea
