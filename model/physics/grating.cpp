#include "model/physics/grating.h"

#include <algorithm>
#include <cctype>

namespace fovea {

std::optional<Polarization> parsePolarization(const std::string& text) {
  std::string t = text;
  std::transform(t.begin(), t.end(), t.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (t == "s" || t == "te") return Polarization::S;
  if (t == "p" || t == "tm") return Polarization::P;
  if (t == "u" || t == "unpolarized" || t == "unpolarised") return Polarization::Unpolarized;
  return std::nullopt;
}

const char* polarizationName(Polarization p) {
  switch (p) {
    case Polarization::S:
      return "s";
    case Polarization::P:
      return "p";
    case Polarization::Unpolarized:
      return "unpolarized";
  }
  return "?";
}

PlanarDiffraction diffractPlanar(const PlanarGrating& g) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  const double lambda_um = g.wavelength_nm * 1e-3;
  const double beta = 2.0 * std::numbers::pi * g.film.n0 / lambda_um;
  const double k = 2.0 * std::numbers::pi / (g.period_nm * 1e-3);
  const double theta = g.probe_deg * kDeg, phi = g.slant_deg * kDeg;
  const double c_r = std::cos(theta);
  const double c_s = std::cos(theta) - k / beta * std::cos(phi);
  const double vartheta = k * std::cos(phi - theta) - k * k / (2.0 * beta);
  // sigma = rho - K in the x-z plane; p factor rho_hat . sigma_hat (see grating.h).
  const double sx = beta * std::sin(theta) - k * std::sin(phi);
  const double sz = beta * c_s;
  const double smag = std::hypot(sx, sz);
  const double p_factor = smag > 0.0 ? (beta - k * std::cos(theta - phi)) / smag : 1.0;

  PlanarDiffraction out;
  out.grating = diffractCore(c_r, c_s, vartheta, p_factor, g.film, lambda_um, g.polarization);
  out.grating.sigma = Eigen::Vector3d(sx, 0.0, sz);
  if (std::abs(sx) >= beta) {
    out.grating.evanescent = true;
    out.grating.kogelnik.zero_order += out.grating.kogelnik.efficiency;
    out.grating.kogelnik.efficiency = 0.0;
  } else {
    const double kz = (c_s < 0.0 ? -1.0 : 1.0) * std::sqrt(beta * beta - sx * sx);
    out.grating.diffracted = Eigen::Vector3d(sx, 0.0, kz);
    double deg = std::atan2(sx, kz) / kDeg;
    if (deg <= -180.0) deg += 360.0;  // (-180, 180]
    out.diffracted_deg = deg;
  }
  return out;
}

}  // namespace fovea
