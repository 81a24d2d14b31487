#pragma once
// One volume grating met by one probe wave: Kogelnik's theory in 3-D (any probe wave vector,
// any grating vector) and its planar special case (Kogelnik's angles theta, phi).
//
// Conventions (docs/physics.md):
//  - film frame: the film normal is +z; inside the film everything is in rad/µm;
//  - Kogelnik's sign: the diffracted wave is sigma = rho - K. A recorded HOE stores
//    K_rec = k_signal - k_reference (seed A.1); its Kogelnik vector is -K_rec;
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
template <class T>
struct FilmGratingT {
  T n0 = T(1.5);  // mean index
  T n1 = 0;       // index modulation amplitude
  T thickness_um = 0;
  T alpha_per_um = 0;  // Kogelnik's *amplitude* absorption constant (half the intensity one)
  template <class U>
  FilmGratingT<U> cast() const {
    return {U(n0), U(n1), U(thickness_um), U(alpha_per_um)};
  }
};
using FilmGrating = FilmGratingT<double>;

template <class T>
using Vec3T = Eigen::Matrix<T, 3, 1>;

template <class T>
struct GratingDiffractionT {
  kogelnik::ResultT<T> kogelnik;           // efficiency, zero order, nu, xi (s or p; averaged if unpolarised)
  T c_r = 0, c_s = 0;                      // obliquity factors
  T vartheta = 0;                          // dephasing, rad/µm
  T p_factor = 1;                          // rho_hat . sigma_hat
  Vec3T<T> sigma = Vec3T<T>::Zero();       // Kogelnik's sigma = rho - K (rad/µm)
  Vec3T<T> diffracted = Vec3T<T>::Zero();  // physical diffracted wave vector inside
  bool evanescent = false;                 // |sigma_t| > beta: the order does not propagate (efficiency 0)
  bool reflection() const { return kogelnik.reflection; }
};
using GratingDiffraction = GratingDiffractionT<double>;

namespace detail {
template <class T>
inline kogelnik::ResultT<T> polarised(T c_r, T c_s, T vartheta, T kappa, T p_factor, T alpha, T d, Polarization pol) {
  if (pol == Polarization::S) return kogelnik::evaluateT<T>(c_r, c_s, vartheta, kappa, alpha, d);
  if (pol == Polarization::P) return kogelnik::evaluateT<T>(c_r, c_s, vartheta, kappa * p_factor, alpha, d);
  kogelnik::ResultT<T> s = kogelnik::evaluateT<T>(c_r, c_s, vartheta, kappa, alpha, d);
  const kogelnik::ResultT<T> p = kogelnik::evaluateT<T>(c_r, c_s, vartheta, kappa * p_factor, alpha, d);
  s.efficiency = T(0.5) * (s.efficiency + p.efficiency);
  s.zero_order = T(0.5) * (s.zero_order + p.zero_order);
  s.nu = T(0.5) * (s.nu + p.nu);  // reported nu: the mean coupling of the two polarisations
  return s;
}
}  // namespace detail

// Shared tail of the planar and 3-D paths: given c_R, c_S, vartheta and the p factor.
template <class T>
inline GratingDiffractionT<T> diffractCoreT(T c_r, T c_s, T vartheta, T p_factor, const FilmGratingT<T>& film,
                                            T wavelength_um, Polarization pol) {
  GratingDiffractionT<T> g;
  g.c_r = c_r;
  g.c_s = c_s;
  g.vartheta = vartheta;
  g.p_factor = p_factor;
  const T kappa = std::numbers::pi_v<T> * film.n1 / wavelength_um;  // Kogelnik Eq. 8, lossless modulation
  g.kogelnik = detail::polarised<T>(c_r, c_s, vartheta, kappa, p_factor, film.alpha_per_um, film.thickness_um, pol);
  return g;
}
inline GratingDiffraction diffractCore(double c_r, double c_s, double vartheta, double p_factor,
                                       const FilmGrating& film, double wavelength_um, Polarization pol) {
  return diffractCoreT<double>(c_r, c_s, vartheta, p_factor, film, wavelength_um, pol);
}

// The geometric part of diffract3d (everything but the coupled-wave solve): obliquity
// factors, dephasing, p factor, sigma and the physical diffracted wave vector.
template <class T>
struct DiffractionGeometryT {
  T c_r = 0, c_s = 0, vartheta = 0, p_factor = 1;
  Vec3T<T> sigma = Vec3T<T>::Zero();       // in the caller's frame (z not mirrored)
  Vec3T<T> diffracted = Vec3T<T>::Zero();  // physical diffracted wave vector (caller's frame)
  bool evanescent = false;
};

// rho: probe wave vector inside (|rho| = beta), k: Kogelnik's grating vector, both rad/µm.
template <class T>
inline DiffractionGeometryT<T> diffractionGeometryT(const Vec3T<T>& rho_in, const Vec3T<T>& k_in, T beta) {
  using std::sqrt;
  DiffractionGeometryT<T> g;
  const T flip = rho_in.z() < T(0) ? T(-1) : T(1);  // mirror z so that the probe travels +z
  const T rz = flip * rho_in.z();
  // sigma = rho - K, component by component (z mirrored).
  const T sx = rho_in.x() - k_in.x(), sy = rho_in.y() - k_in.y(), sz = rz - flip * k_in.z();
  const T t2 = sx * sx + sy * sy;
  const T sigma2 = t2 + sz * sz;
  g.c_r = rz / beta;
  g.c_s = sz / beta;
  g.vartheta = (beta * beta - sigma2) / (T(2) * beta);  // Kogelnik Eq. 17 in vector form
  g.p_factor = sigma2 > T(0) ? (rho_in.x() * sx + rho_in.y() * sy + rz * sz) / (beta * sqrt(sigma2)) : T(1);
  g.sigma = Vec3T<T>(sx, sy, flip * sz);
  if (t2 >= beta * beta) {
    g.evanescent = true;
  } else {
    const T kz = (g.c_s < T(0) ? T(-1) : T(1)) * sqrt(beta * beta - t2);
    g.diffracted = Vec3T<T>(sx, sy, flip * kz);
  }
  return g;
}

// 3-D: rho is the probe wave vector inside the film (|rho| = beta = 2 pi n0 / lambda, any
// direction with rho_z != 0), K the grating vector in Kogelnik's sign. Pure, allocation-free.
template <class T>
inline GratingDiffractionT<T> diffract3dT(const Vec3T<T>& rho_in, const Vec3T<T>& k_in, const FilmGratingT<T>& film,
                                          T wavelength_um, Polarization pol) {
  const T beta = T(2) * std::numbers::pi_v<T> * film.n0 / wavelength_um;
  const DiffractionGeometryT<T> geo = diffractionGeometryT<T>(rho_in, k_in, beta);
  GratingDiffractionT<T> g = diffractCoreT<T>(geo.c_r, geo.c_s, geo.vartheta, geo.p_factor, film, wavelength_um, pol);
  g.sigma = geo.sigma;
  g.evanescent = geo.evanescent;
  g.diffracted = geo.diffracted;
  if (geo.evanescent) {
    g.kogelnik.zero_order =
        std::min(T(1), g.kogelnik.zero_order + g.kogelnik.efficiency);  // nothing leaves in the order
    g.kogelnik.efficiency = T(0);
  }
  return g;
}
inline GratingDiffraction diffract3d(const Eigen::Vector3d& rho_in, const Eigen::Vector3d& k_in,
                                     const FilmGrating& film, double wavelength_um, Polarization pol) {
  return diffract3dT<double>(rho_in, k_in, film, wavelength_um, pol);
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

template <class T>
struct PlanarDiffractionT {
  GratingDiffractionT<T> grating;
  std::optional<T> diffracted_deg;  // angle of the diffracted wave from +z, (-180, 180]
};
using PlanarDiffraction = PlanarDiffractionT<double>;

// Kogelnik's scalar formulas: c_R = cos theta, c_S = cos theta - (K/beta) cos phi,
// vartheta = K cos(phi - theta) - K^2 / (2 beta) (Kogelnik Eqs. 17, 23, 24). The inputs are
// taken as given (double) and everything is evaluated in T.
template <class T>
PlanarDiffractionT<T> diffractPlanarT(const PlanarGrating& g) {
  using std::cos, std::sin, std::sqrt, std::abs;
  const T pi = std::numbers::pi_v<T>;
  const T deg = pi / T(180);
  const T milli = T(1) / T(1000);  // 1e-3 rounded in T
  const T lambda_um = T(g.wavelength_nm) * milli;
  const T beta = T(2) * pi * T(g.film.n0) / lambda_um;
  const T k = T(2) * pi / (T(g.period_nm) * milli);
  const T theta = T(g.probe_deg) * deg, phi = T(g.slant_deg) * deg;
  const T c_r = cos(theta);
  const T c_s = cos(theta) - k / beta * cos(phi);
  const T vartheta = k * cos(phi - theta) - k * k / (T(2) * beta);
  // sigma = rho - K in the x-z plane; p factor rho_hat . sigma_hat (see above).
  const T sx = beta * sin(theta) - k * sin(phi);
  const T sz = beta * c_s;
  const T smag = std::hypot(sx, sz);
  const T p_factor = smag > T(0) ? (beta - k * cos(theta - phi)) / smag : T(1);

  PlanarDiffractionT<T> out;
  out.grating = diffractCoreT<T>(c_r, c_s, vartheta, p_factor, g.film.cast<T>(), lambda_um, g.polarization);
  out.grating.sigma = Vec3T<T>(sx, T(0), sz);
  if (abs(sx) >= beta) {
    out.grating.evanescent = true;
    out.grating.kogelnik.zero_order = std::min(T(1), out.grating.kogelnik.zero_order + out.grating.kogelnik.efficiency);
    out.grating.kogelnik.efficiency = T(0);
  } else {
    const T kz = (c_s < T(0) ? T(-1) : T(1)) * sqrt(beta * beta - sx * sx);
    out.grating.diffracted = Vec3T<T>(sx, T(0), kz);
    T angle = std::atan2(sx, kz) / deg;
    if (angle <= T(-180)) angle += T(360);  // (-180, 180]
    out.diffracted_deg = angle;
  }
  return out;
}

PlanarDiffraction diffractPlanar(const PlanarGrating& g);

}  // namespace fovea
