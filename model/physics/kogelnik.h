#pragma once
// Kogelnik's two-wave coupled-wave theory of thick gratings (H. Kogelnik, "Coupled wave
// theory for thick hologram gratings", Bell Syst. Tech. J. 48, 2909 (1969)), in forms that
// stay finite and accurate everywhere (docs/physics.md has the derivation).
//
// Units: lengths in micrometres, wave numbers in rad/µm. The film occupies 0 <= z <= d, its
// normal is +z and the probe R enters at z = 0 travelling towards +z (c_R > 0).
//
// Coupled equations (Kogelnik Eq. 19, 20), alpha the mean *amplitude* absorption constant:
//   c_R R' + alpha R = -i kappa S,   c_S S' + (alpha + i vartheta) S = -i kappa R
// with kappa = pi n1 / lambda (times the polarisation coupling factor), c_R = rho_z / beta,
// c_S = sigma_z / beta, sigma = rho - K, beta = 2 pi n0 / lambda and the dephasing
// vartheta = (beta^2 - |sigma|^2) / (2 beta).
//
// c_S > 0: transmission geometry, R(0) = 1, S(0) = 0, eta = (c_S/c_R) |S(d)|^2.
// c_S < 0: reflection geometry,   R(0) = 1, S(d) = 0, eta = (|c_S|/c_R) |S(0)|^2.
//
// Lossless closed forms, rewritten without singular quotients:
//   transmission  eta = nu^2 shc(-(nu^2 + xi^2))^2                (= Kogelnik Eq. 43)
//   reflection    eta = 1 / (1 + 1 / (nu^2 shc(nu^2 - xi^2)^2))   (= Kogelnik Eq. 56)
// where shc(u2) = sinh(sqrt(u2))/sqrt(u2) for u2 > 0, sin(sqrt(-u2))/sqrt(-u2) for u2 < 0 and
// 1 at u2 = 0: one analytic (entire) function of u2, so the reflection branch change at
// nu^2 = xi^2 is continuous by construction and nu -> 0 is finite.
// Absorbing media: the 2x2 system is solved exactly by its matrix exponential (kogelnik.cpp).

#include <cmath>

namespace fovea::kogelnik {

struct Result {
  double efficiency = 0.0;  // diffracted power / incident power (obliquity-normalised)
  double zero_order = 1.0;  // power left in the undiffracted (transmitted) probe
  double nu = 0.0;          // coupling strength |kappa| d / sqrt(c_R |c_S|)
  double xi = 0.0;          // dephasing |vartheta| d / (2 |c_S|)
  bool reflection = false;  // c_S < 0
};

// sinh(sqrt(u2)) / sqrt(u2), continued analytically to u2 <= 0 (sin branch). Entire in u2.
inline double shc(double u2) {
  if (std::abs(u2) < 1e-4) return 1.0 + u2 / 6.0 * (1.0 + u2 / 20.0);  // next term u2^3/5040 < 3e-16
  if (u2 > 0.0) {
    const double u = std::sqrt(u2);
    return std::sinh(u) / u;  // +inf beyond u ~ 710: eta -> 1 below, which is the limit
  }
  const double u = std::sqrt(-u2);
  return std::sin(u) / u;
}

// Directions below this |c_S| are treated as grazing: the diffracted wave runs along the film
// and carries no power out (the limit of both closed forms as c_S -> 0 with vartheta != 0).
inline constexpr double kGrazingCs = 1e-12;

// Lossless film. kappa already includes the polarisation factor. Allocation-free, inline: this
// is the inner loop of every trace.
inline Result lossless(double c_r, double c_s, double vartheta, double kappa, double d) {
  Result r;
  r.reflection = c_s < 0.0;
  if (!(c_r > 0.0) || !(d > 0.0) || std::abs(c_s) < kGrazingCs) return r;
  const double acs = std::abs(c_s);
  r.nu = std::abs(kappa) * d / std::sqrt(c_r * acs);
  r.xi = std::abs(vartheta) * d / (2.0 * acs);
  const double nu2 = r.nu * r.nu, xi2 = r.xi * r.xi;
  if (!r.reflection) {
    const double s = shc(-(nu2 + xi2));
    r.efficiency = nu2 * s * s;  // = sin^2(sqrt(nu^2+xi^2)) / (1 + xi^2/nu^2)
  } else {
    const double g = r.nu * shc(nu2 - xi2);
    r.efficiency = 1.0 / (1.0 + 1.0 / (g * g));  // g = 0 -> 0, g = inf -> 1
  }
  r.zero_order = 1.0 - r.efficiency;
  return r;
}

// General film with mean amplitude absorption alpha (1/µm, >= 0). Exact solution of the
// coupled equations via the closed-form 2x2 matrix exponential; equals lossless() at alpha = 0.
Result absorbing(double c_r, double c_s, double vartheta, double kappa, double alpha, double d);

// Dispatch: the fast lossless path when alpha == 0.
inline Result evaluate(double c_r, double c_s, double vartheta, double kappa, double alpha, double d) {
  return alpha > 0.0 ? absorbing(c_r, c_s, vartheta, kappa, alpha, d) : lossless(c_r, c_s, vartheta, kappa, d);
}

}  // namespace fovea::kogelnik
