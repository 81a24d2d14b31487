#include "model/physics/eye_oblique_focus.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "model/physics/schematic_eye.h"
#include "model/units.h"

namespace fovea {

namespace {

struct P2 {
  double y = 0, z = 0;
};
P2 operator+(P2 a, P2 b) {
  return {a.y + b.y, a.z + b.z};
}
P2 operator-(P2 a, P2 b) {
  return {a.y - b.y, a.z - b.z};
}
P2 operator*(double k, P2 a) {
  return {k * a.y, k * a.z};
}
double dot(P2 a, P2 b) {
  return a.y * b.y + a.z * b.z;
}

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

// Nearest forward intersection with the conic's branch through its vertex.
std::optional<P2> hitConic(const ConicSurface& s, P2 p, P2 u) {
  const double w0 = p.z - s.vertex_z, k1 = 1.0 + s.Q;
  // c (y^2 + (1+Q) w^2) - 2 w = 0 along p + t u.
  const double a = s.c * (u.y * u.y + k1 * u.z * u.z);
  const double b = 2.0 * s.c * (p.y * u.y + k1 * w0 * u.z) - 2.0 * u.z;
  const double k = s.c * (p.y * p.y + k1 * w0 * w0) - 2.0 * w0;
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
    const double y = p.y + t * u.y, w = w0 + t * u.z;
    const double under = 1.0 - k1 * s.c * s.c * y * y;
    if (under < 0) continue;
    const double sag = s.c * y * y / (1.0 + std::sqrt(under));
    if (std::abs(w - sag) < 1e-7) best = t;
  }
  if (!std::isfinite(best)) return std::nullopt;
  return p + best * u;
}

// Unit normal at a point of the conic, oriented along the ray u.
P2 conicNormal(const ConicSurface& s, P2 at, P2 u) {
  const double w = at.z - s.vertex_z;
  P2 g{2.0 * s.c * at.y, 2.0 * s.c * (1.0 + s.Q) * w - 2.0};
  g = (1.0 / std::sqrt(dot(g, g))) * g;
  return dot(g, u) < 0 ? -1.0 * g : g;
}

struct Refracted {
  P2 u;
  double cos_in, cos_out;
};
std::optional<Refracted> refract(P2 u, P2 normal, double n, double n2) {
  const double eta = n / n2, ci = dot(u, normal);
  const double s2 = eta * eta * (1.0 - ci * ci);
  if (s2 > 1.0) return std::nullopt;  // total internal reflection
  const double co = std::sqrt(1.0 - s2);
  return Refracted{eta * u + (co - eta * ci) * normal, ci, co};
}

// The real chief ray at field theta: its crossing of the paraxial entrance-pupil plane.
struct ChiefRay {
  bool valid = false;
  double h = 0;  // height at the entrance-pupil plane
  P2 u;          // direction in air
};

// Height at the stop plane (lens' front vertex) of the air ray through (h, E) along u.
std::optional<double> heightAtStop(const std::array<ConicSurface, 4>& s, double entrance_z, double h, P2 u) {
  P2 p = P2{h, entrance_z} - 30.0 * u;
  for (int i = 0; i < 2; ++i) {
    const auto hit = hitConic(s[i], p, u);
    if (!hit) return std::nullopt;
    const auto r = refract(u, conicNormal(s[i], *hit, u), s[i].n_before, s[i].n_after);
    if (!r) return std::nullopt;
    p = *hit;
    u = r->u;
  }
  if (!(u.z > 1e-9)) return std::nullopt;
  return p.y + (s[2].vertex_z - p.z) / u.z * u.y;
}

ChiefRay findChiefRay(const std::array<ConicSurface, 4>& s, double entrance_z, double theta_rad) {
  ChiefRay c;
  c.u = {std::sin(theta_rad), std::cos(theta_rad)};
  double h0 = 0.0, h1 = 0.01;
  auto f0 = heightAtStop(s, entrance_z, h0, c.u), f1 = heightAtStop(s, entrance_z, h1, c.u);
  for (int it = 0; it < 60 && f0 && f1; ++it) {
    if (std::abs(*f1) < 1e-13) break;
    const double den = *f1 - *f0;
    if (std::abs(den) < 1e-300) return c;
    const double h2 = h1 - *f1 * (h1 - h0) / den;
    h0 = h1;
    f0 = f1;
    h1 = h2;
    f1 = heightAtStop(s, entrance_z, h1, c.u);
  }
  if (!f1 || std::abs(*f1) > 1e-9) return c;
  c.h = h1;
  c.valid = true;
  return c;
}

// Ray geometry of the chief ray through the eye (independent of the pencil's vergence).
struct ChiefPath {
  bool valid = false;
  std::array<P2, 4> hit{};
  std::array<double, 4> cos_in{}, cos_out{}, k_m{}, k_s{}, along{};  // along: distance from the previous hit
  double pupil_to_first = 0;  // from the entrance-pupil crossing back to the corneal hit (> 0)
  P2 u_last;
  double retina = 0;
};

ChiefPath tracePath(const std::array<ConicSurface, 4>& s, double entrance_z, const ChiefRay& c, double axial_length) {
  ChiefPath path;
  const P2 pupil{c.h, entrance_z};
  P2 p = pupil - 30.0 * c.u, u = c.u;
  for (int i = 0; i < 4; ++i) {
    const auto hit = hitConic(s[i], p, u);
    if (!hit) return path;
    const auto r = refract(u, conicNormal(s[i], *hit, u), s[i].n_before, s[i].n_after);
    if (!r) return path;
    const double rr = hit->y, q = 1.0 - s[i].Q * s[i].c * s[i].c * rr * rr;
    if (!(q > 0)) return path;
    path.hit[i] = *hit;
    path.cos_in[i] = r->cos_in;
    path.cos_out[i] = r->cos_out;
    path.k_m[i] = s[i].c / (q * std::sqrt(q));
    path.k_s[i] = s[i].c / std::sqrt(q);
    path.along[i] = i == 0 ? 0.0 : std::sqrt(dot(*hit - p, *hit - p));
    if (i == 0) path.pupil_to_first = dot(pupil - *hit, c.u);
    p = *hit;
    u = r->u;
  }
  // The retina: sphere of radius |R| about (0, L + R), the far intersection.
  const P2 centre{0.0, axial_length + kNavarroRetinaRadiusMm};
  const P2 d = p - centre;
  const double b = dot(d, u), k = dot(d, d) - kNavarroRetinaRadiusMm * kNavarroRetinaRadiusMm;
  const double disc = b * b - k;
  if (disc < 0) return path;
  path.retina = -b + std::sqrt(disc);
  if (!(path.retina > 0)) return path;
  path.u_last = u;
  path.valid = true;
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

}  // namespace

ChiefRayFoci navarroChiefRayFoci(const SchematicEyeState& eye, double field_deg, double vergence_d) {
  if (!std::isfinite(field_deg) || std::abs(field_deg) > 60.0)
    throw std::invalid_argument("eye field angle must be within -60..60 deg");
  const auto surfaces = eyeSurfaces(eye);
  ChiefRayFoci f;
  const ChiefRay c = findChiefRay(surfaces, eye.entrance_pupil_mm, field_deg * kDeg);
  if (!c.valid) return f;
  const ChiefPath path = tracePath(surfaces, eye.entrance_pupil_mm, c, eye.axial_length_mm);
  if (!path.valid) return f;
  const auto v = pencil(surfaces, path, vergence_d / 1000.0);
  f.valid = true;
  f.pupil_height_mm = c.h;
  f.last_hit_y_mm = path.hit[3].y;
  f.last_hit_z_mm = path.hit[3].z;
  f.direction_y = path.u_last.y;
  f.direction_z = path.u_last.z;
  f.tangential_mm = v[0] == 0 ? std::numeric_limits<double>::infinity() : 1.0 / v[0];
  f.sagittal_mm = v[1] == 0 ? std::numeric_limits<double>::infinity() : 1.0 / v[1];
  f.retina_mm = path.retina;
  return f;
}

EyeObliqueFocus eyeObliqueFocus(const SchematicEyeState& eye, double field_deg) {
  if (!std::isfinite(field_deg) || std::abs(field_deg) > 60.0)
    throw std::invalid_argument("eye field angle must be within -60..60 deg");
  const auto surfaces = eyeSurfaces(eye);
  EyeObliqueFocus out;
  out.field_deg = field_deg;
  auto focusAt = [&](double theta_deg) -> std::optional<std::array<double, 2>> {
    const ChiefRay c = findChiefRay(surfaces, eye.entrance_pupil_mm, theta_deg * kDeg);
    if (!c.valid) return std::nullopt;
    const ChiefPath path = tracePath(surfaces, eye.entrance_pupil_mm, c, eye.axial_length_mm);
    if (!path.valid) return std::nullopt;
    const double start = -eye.accommodation_d / 1000.0;
    const auto t = focusedVergence(surfaces, path, 0, start), s = focusedVergence(surfaces, path, 1, start);
    if (!t || !s) return std::nullopt;
    return std::array<double, 2>{*t * 1000.0, *s * 1000.0};
  };
  const auto axis = focusAt(0.0), at = focusAt(std::abs(field_deg));
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

}  // namespace fovea
