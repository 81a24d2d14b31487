#include "model/rigorous/planar_case.h"

#include <cmath>

#include "model/units.h"

namespace fovea::rigorous {

namespace {
struct Geometry {
  double cr, cs, vartheta, p_factor;
};
Geometry geometry(const PlanarCase& c) {
  const double lam = c.wavelength_nm * 1e-3, L = c.period_nm * 1e-3, K = 2 * kPi / L;
  const double th = c.probe_deg * kPi / 180.0, ph = c.slant_deg * kPi / 180.0;
  Geometry g;
  g.cr = std::cos(th);
  g.cs = std::cos(th) - lam / (c.n0 * L) * std::cos(ph);
  g.vartheta = K * std::cos(ph - th) - K * K * lam / (4 * kPi * c.n0);
  const double beta = 2 * kPi * c.n0 / lam;
  const double rx = beta * std::sin(th), rz = beta * std::cos(th);
  const double sx = rx - K * std::sin(ph), sz = rz - K * std::cos(ph);
  g.p_factor = (rx * sx + rz * sz) / (beta * std::hypot(sx, sz));  // ρ̂·σ̂
  return g;
}
}  // namespace

KogelnikEvaluation kogelnikClosedForm(const PlanarCase& c) {
  const Geometry g = geometry(c);
  const double lam = c.wavelength_nm * 1e-3, d = c.thickness_um;
  KogelnikEvaluation k;
  k.reflection = g.cs < 0.0;
  if (std::abs(g.cs) < 1e-12 || !(d > 0.0) || c.n1 == 0.0) return k;
  const double coupling = c.te ? 1.0 : std::abs(g.p_factor);
  k.nu = kPi * c.n1 * coupling * d / (lam * std::sqrt(std::abs(g.cr * g.cs)));
  k.xi = std::abs(g.vartheta) * d / (2 * std::abs(g.cs));
  const double nu2 = k.nu * k.nu, xi2 = k.xi * k.xi;
  if (nu2 == 0.0) return k;
  if (!k.reflection) {
    const double s = std::sqrt(nu2 + xi2);
    k.efficiency = std::pow(std::sin(s), 2) / (1 + xi2 / nu2);
  } else {
    const double q = nu2 - xi2;
    double denom;
    if (q > 0)
      denom = 1 + (1 - xi2 / nu2) / std::pow(std::sinh(std::sqrt(q)), 2);
    else if (q < 0)
      denom = 1 + (xi2 / nu2 - 1) / std::pow(std::sin(std::sqrt(-q)), 2);
    else
      denom = 1 + 1 / nu2;
    k.efficiency = 1 / denom;
  }
  return k;
}

RcwaProblem rcwaProblemOf(const PlanarCase& c) {
  RcwaProblem p;
  p.n0 = c.n0;
  p.n1 = c.n1;
  p.thickness_um = c.thickness_um;
  p.period_nm = c.period_nm;
  p.slant_deg = c.slant_deg;
  p.wavelength_nm = c.wavelength_nm;
  p.n_cover = p.n_substrate = c.n0;
  p.polarization = c.te ? RcwaPolarization::TE : RcwaPolarization::TM;
  p.setFilmAngleDeg(c.probe_deg);
  return p;
}

double kogelnikXi(const PlanarCase& c) {
  const Geometry g = geometry(c);
  return std::abs(g.vartheta) * c.thickness_um / (2 * std::max(1e-12, std::abs(g.cs)));
}
double rhoParameter(const PlanarCase& c) {
  return std::pow(c.wavelength_nm / c.period_nm, 2) / (c.n0 * c.n1);
}
double kleinQ(const PlanarCase& c) {
  const double L = c.period_nm * 1e-3;
  return 2 * kPi * c.wavelength_nm * 1e-3 * c.thickness_um / (c.n0 * L * L);
}

}  // namespace fovea::rigorous
