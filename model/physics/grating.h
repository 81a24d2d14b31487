#pragma once
// One volume grating met by one probe wave: Kogelnik's theory in 3-D (any probe wave vector,
// any grating vector) and its planar special case (Kogelnik's angles theta, phi).
//
// Conventions (docs/physics.md):
//  - film frame: the film normal is +z; inside the film everything is in rad/µm;
//  - Kogelnik's sign: the diffracted wave is sigma = rho - K. A recorded HOE stores
//    K_rec = k_signal - k_reference (issue 4 / seed A.1); its Kogelnik vector is -K_rec;
//  - polarisation: s is normal to the plane of rho and sigma; p lies in it. The coupling
//    constant is kappa (e_R . e_S): 1 for s, rho_hat . sigma_hat for p (= -cos 2(theta - phi)
//    on Bragg, Kogelnik's p factor); unpolarised light averages the s and p efficiencies;
//  - a probe travelling towards -z is handled by mirroring z (the film is symmetric).

#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "model/physics/kogelnik.h"

namespace fovea {

enum class Polarization { S, P, Unpolarized };

// "s", "p", "unpolarized"/"unpolarised"/"u" (case-insensitive) -> value; nullopt otherwise.
std::optional<Polarization> parsePolarization(const std::string& text);
const char* polarizationName(Polarization p);

// Material of one grating layer.
struct FilmGrating {
  double n0 = 1.5;  // mean index
  double n1 = 0.0;  // index modulation amplitude
  double thickness_um = 0.0;
  double alpha_per_um = 0.0;  // Kogelnik's *amplitude* absorption constant (half the intensity one)
};

struct GratingDiffraction {
  kogelnik::Result kogelnik;                        // efficiency, zero order, nu, xi (s or p; averaged if unpolarised)
  double c_r = 0.0, c_s = 0.0;                      // obliquity factors
  double vartheta = 0.0;                            // dephasing, rad/µm
  double p_factor = 1.0;                            // rho_hat . sigma_hat
  Eigen::Vector3d sigma = Eigen::Vector3d::Zero();  // Kogelnik's sigma = rho - K (rad/µm)
  Eigen::Vector3d diffracted = Eigen::Vector3d::Zero();  // physical diffracted wave vector inside
  bool evanescent = false;  // |sigma_t| > beta: the order does not propagate (efficiency 0)
  bool reflection() const { return kogelnik.reflection; }
};

namespace detail {
inline kogelnik::Result polarised(double c_r, double c_s, double vartheta, double kappa, double p_factor, double alpha,
                                  double d, Polarization pol) {
  if (pol == Polarization::S) return kogelnik::evaluate(c_r, c_s, vartheta, kappa, alpha, d);
  if (pol == Polarization::P) return kogelnik::evaluate(c_r, c_s, vartheta, kappa * p_factor, alpha, d);
  kogelnik::Result s = kogelnik::evaluate(c_r, c_s, vartheta, kappa, alpha, d);
  const kogelnik::Result p = kogelnik::evaluate(c_r, c_s, vartheta, kappa * p_factor, alpha, d);
  s.efficiency = 0.5 * (s.efficiency + p.efficiency);
  s.zero_order = 0.5 * (s.zero_order + p.zero_order);
  s.nu = 0.5 * (s.nu + p.nu);  // reported nu: the mean coupling of the two polarisations
  return s;
}
}  // namespace detail

// Shared tail of the planar and 3-D paths: given c_R, c_S, vartheta and the p factor.
inline GratingDiffraction diffractCore(double c_r, double c_s, double vartheta, double p_factor,
                                       const FilmGrating& film, double wavelength_um, Polarization pol) {
  GratingDiffraction g;
  g.c_r = c_r;
  g.c_s = c_s;
  g.vartheta = vartheta;
  g.p_factor = p_factor;
  const double kappa = std::numbers::pi * film.n1 / wavelength_um;  // Kogelnik Eq. 8, lossless modulation
  g.kogelnik = detail::polarised(c_r, c_s, vartheta, kappa, p_factor, film.alpha_per_um, film.thickness_um, pol);
  return g;
}

// 3-D: rho is the probe wave vector inside the film (|rho| = beta = 2 pi n0 / lambda, any
// direction with rho_z != 0), K the grating vector in Kogelnik's sign. Pure, allocation-free.
inline GratingDiffraction diffract3d(const Eigen::Vector3d& rho_in, const Eigen::Vector3d& k_in,
                                     const FilmGrating& film, double wavelength_um, Polarization pol) {
  const double beta = 2.0 * std::numbers::pi * film.n0 / wavelength_um;
  const double flip = rho_in.z() < 0.0 ? -1.0 : 1.0;  // mirror z so that the probe travels +z
  const Eigen::Vector3d rho(rho_in.x(), rho_in.y(), flip * rho_in.z());
  const Eigen::Vector3d kg(k_in.x(), k_in.y(), flip * k_in.z());
  const Eigen::Vector3d sigma = rho - kg;
  const double sigma2 = sigma.squaredNorm();
  const double c_r = rho.z() / beta;
  const double c_s = sigma.z() / beta;
  const double vartheta = (beta * beta - sigma2) / (2.0 * beta);  // Kogelnik Eq. 17 in vector form
  const double p_factor = sigma2 > 0.0 ? rho.dot(sigma) / (beta * std::sqrt(sigma2)) : 1.0;
  GratingDiffraction g = diffractCore(c_r, c_s, vartheta, p_factor, film, wavelength_um, pol);
  g.sigma = Eigen::Vector3d(sigma.x(), sigma.y(), flip * sigma.z());
  const double t2 = sigma.x() * sigma.x() + sigma.y() * sigma.y();
  if (t2 >= beta * beta) {
    g.evanescent = true;
    g.kogelnik.zero_order = g.kogelnik.zero_order + g.kogelnik.efficiency;  // nothing leaves in the order
    g.kogelnik.efficiency = 0.0;
  } else {
    const double kz = (c_s < 0.0 ? -1.0 : 1.0) * std::sqrt(beta * beta - t2);
    g.diffracted = Eigen::Vector3d(sigma.x(), sigma.y(), flip * kz);
  }
  return g;
}

// Planar grating in the x-z plane (Kogelnik's geometry), all inputs in the film.
struct PlanarGrating {
  FilmGrating film;
  double period_nm = 0.0;
  double slant_deg = 0.0;      // phi: angle of K from the film normal
  double probe_deg = 0.0;      // theta: angle of rho from the film normal (inside the medium)
  double wavelength_nm = 0.0;  // vacuum wavelength
  Polarization polarization = Polarization::S;
};

struct PlanarDiffraction {
  GratingDiffraction grating;
  std::optional<double> diffracted_deg;  // angle of the diffracted wave from +z, (-180, 180]
};

// Kogelnik's scalar formulas: c_R = cos theta, c_S = cos theta - (K/beta) cos phi,
// vartheta = K cos(phi - theta) - K^2 / (2 beta) (Kogelnik Eqs. 17, 23, 24).
PlanarDiffraction diffractPlanar(const PlanarGrating& g);

}  // namespace fovea
