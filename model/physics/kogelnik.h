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
// Absorbing media: the 2x2 system is solved exactly by its matrix exponential.
//
// Every function is a template on the floating type T (float, double, long double): the
// studio runs double; long double is the reference of the stability suite
// (tests/model/tst_numerical_stability.cpp) and float the precision benchmark. The double
// names (Result, lossless, absorbing, evaluate) are the ones the rest of the code uses.

#include <algorithm>
#include <cmath>
#include <complex>

namespace fovea::kogelnik {

template <class T>
struct ResultT {
  T efficiency = 0;         // diffracted power / incident power (obliquity-normalised)
  T zero_order = 1;         // power left in the undiffracted (transmitted) probe
  T nu = 0;                 // coupling strength |kappa| d / sqrt(c_R |c_S|)
  T xi = 0;                 // dephasing |vartheta| d / (2 |c_S|)
  bool reflection = false;  // c_S < 0
};
using Result = ResultT<double>;

// sinh(sqrt(u2)) / sqrt(u2), continued analytically to u2 <= 0 (sin branch). Entire in u2.
// Near 0 the Taylor series 1 + u2/3! + u2^2/5! + u2^3/7! + u2^4/9!: the first dropped term,
// u2^5/11! < 3e-28 for |u2| < 1e-4, is below the rounding of every type used.
template <class T>
inline T shc(T u2) {
  using std::abs, std::sqrt, std::sin, std::sinh;
  if (abs(u2) < T(1e-4)) return T(1) + u2 / T(6) * (T(1) + u2 / T(20) * (T(1) + u2 / T(42) * (T(1) + u2 / T(72))));
  if (u2 > T(0)) {
    const T u = sqrt(u2);
    return sinh(u) / u;  // +inf beyond u ~ 710 (double): eta -> 1 below, which is the limit
  }
  const T u = sqrt(-u2);
  return sin(u) / u;
}

// cosh(sqrt(u2)), continued to u2 <= 0 as cos(sqrt(-u2)): also entire in u2.
template <class T>
inline T chc(T u2) {
  using std::abs, std::sqrt, std::cos, std::cosh;
  if (abs(u2) < T(1e-4)) return T(1) + u2 / T(2) * (T(1) + u2 / T(12) * (T(1) + u2 / T(30) * (T(1) + u2 / T(56))));
  return u2 > T(0) ? cosh(sqrt(u2)) : cos(sqrt(-u2));
}

// min(1, x) that keeps a NaN a NaN: std::min(T(1), NaN) is 1, which turned overflowed
// intermediate results (inf - inf) into "full diffraction" instead of exposing them.
template <class T>
inline T atMostOne(T x) {
  return x > T(1) ? T(1) : x;
}

// Directions below this |c_S| are treated as grazing: the diffracted wave runs along the film
// and carries no power out (the limit of both closed forms as c_S -> 0 with vartheta != 0).
inline constexpr double kGrazingCs = 1e-12;

// Lossless film. kappa already includes the polarisation factor. Allocation-free, inline: this
// is the inner loop of every trace.
template <class T>
inline ResultT<T> losslessT(T c_r, T c_s, T vartheta, T kappa, T d) {
  using std::abs, std::sqrt;
  ResultT<T> r;
  r.reflection = c_s < T(0);
  if (!(c_r > T(0)) || !(d > T(0)) || abs(c_s) < T(kGrazingCs)) return r;
  const T acs = abs(c_s);
  r.nu = abs(kappa) * d / sqrt(c_r * acs);
  r.xi = abs(vartheta) * d / (T(2) * acs);
  const T nu2 = r.nu * r.nu;
  // The zero order is computed in its own closed form, not as 1 - eta: next to full conversion
  // (eta = 1 - 1e-12) the difference would keep only a few digits.
  if (!r.reflection) {
    const T u2 = -(nu2 + r.xi * r.xi);
    const T s = shc(u2), c = chc(u2);
    // = sin^2(sqrt(nu^2+xi^2)) / (1 + xi^2/nu^2) and cos^2 + xi^2 sin^2/(nu^2+xi^2) = |R(d)|^2;
    // rounding can carry either an ulp above 1.
    r.efficiency = atMostOne(nu2 * s * s);
    r.zero_order = atMostOne(c * c + r.xi * r.xi * s * s);
  } else {
    // nu^2 - xi^2 as a product: no cancellation next to the branch change nu = xi.
    const T g = r.nu * shc((r.nu - r.xi) * (r.nu + r.xi));
    const T g2 = g * g;
    r.efficiency = T(1) / (T(1) + T(1) / g2);  // g = 0 -> 0, g = inf -> 1
    r.zero_order = T(1) / (T(1) + g2);         // = 1 - eta
  }
  return r;
}

// Write the coupled equations as y' = M y, y = (R, S):
//   M = [[m11, n12], [n21, m22]] = [[-alpha/c_R, -i kappa/c_R], [-i kappa/c_S, -(alpha + i vartheta)/c_S]].
// With m = tr(M)/2, n11 = (m11 - m22)/2, N = M - m I (N^2 = q^2 I, q^2 = n11^2 + n12 n21):
//   exp(M d) = e^{m d} (cosh(Q) I + d sinh(Q)/Q N),  Q = q d.
// Transmission: S(d) = T21, R(d) = T11. Reflection (S(d) = 0): S(0) = -T21/T22 and
// R(d) = det(T)/T22.
// |Q| < 1/2: the cosh/sinh form above (series in Q^2 below |Q^2| = 1e-6).
// |Q| >= 1/2: the eigen form. The branch of q is taken along n11, so s = n11 + q has no
// cancellation and w = q - n11 = n12 n21 / s; the eigenvalues are lambda+ = m11 + w and
// lambda- = m22 - w (never m +- q, which cancels when |m22| >> |m11|: a thick absorbing film
// with a grazing diffracted wave), with E+- = e^{lambda+- d}:
//   T11 = (s E+ + w E-)/(2q), T21 = n21 (E+ - E-)/(2q), T22 = (w E+ + s E-)/(2q), det T = E+ E-.
// Reflection divides by the dominant exponential first (rho = e^{-2Q} or e^{2Q}, |rho| <= 1),
// so growing exponentials neither overflow nor produce inf/inf.
template <class T>
ResultT<T> absorbingT(T c_r, T c_s, T vartheta, T kappa, T alpha, T d) {
  using C = std::complex<T>;
  using std::abs, std::sqrt;
  const C kI{T(0), T(1)};
  ResultT<T> r;
  r.reflection = c_s < T(0);
  if (!(c_r > T(0)) || !(d > T(0)) || abs(c_s) < T(kGrazingCs)) return r;
  const T acs = abs(c_s);
  r.nu = abs(kappa) * d / sqrt(c_r * acs);
  r.xi = abs(vartheta) * d / (T(2) * acs);
  // Without modulation (kappa = 0) nothing couples into S and Eq. 19 gives R(d) = e^{-alpha d / c_R}
  // exactly. The same holds, to far below the rounding of T, when alpha/c_R, alpha/|c_S| or
  // vartheta/|c_S| exceed the floating range (probe or diffracted wave at grazing incidence in a
  // strongly absorbing film): S is then slaved to R with |S| <= kappa |R| / |alpha + i vartheta|
  // (quasi-static limit of Eq. 20), and the matrix below would hold inf and give inf - inf = NaN.
  using std::isfinite;
  if (kappa == T(0) || !isfinite(alpha / c_r) || !isfinite(alpha / acs) || !isfinite(vartheta / acs)) {
    r.efficiency = T(0);
    r.zero_order = std::exp(T(-2) * (alpha * d) / c_r);
    return r;
  }

  const C m11 = -alpha / c_r;
  const C m22 = -(alpha + kI * vartheta) / c_s;
  const C n12 = -kI * kappa / c_r;
  const C n21 = -kI * kappa / c_s;
  const C n11 = T(0.5) * (m11 - m22);
  const C p = n12 * n21;
  // q = sqrt(n11^2 + p) on the branch along n11. For |n11| > 1 it is formed as
  // n11 sqrt(1 + p/n11^2) (principal root: Re(q conj n11) >= 0 by construction), so that n11^2
  // cannot overflow (|n11| > 1e154 in double: a thick, strongly absorbing film).
  C q;
  if (std::abs(n11) > T(1)) {
    q = n11 * std::sqrt(T(1) + (p / n11) / n11);
  } else {
    q = std::sqrt(n11 * n11 + p);
    if (std::real(q * std::conj(n11)) < T(0)) q = -q;
  }
  const C qd = q * d;  // Q
  C s_out, r_out;      // transmission: S(d), R(d); reflection: S(0), R(d)

  if (std::abs(qd) < T(0.5)) {
    const C md = T(0.5) * (m11 + m22) * d;
    const C n22 = -n11;
    const C q2d2 = qd * qd;
    const bool small = std::abs(q2d2) < T(1e-6);
    if (!r.reflection) {
      C a, b;  // a = e^{md} cosh Q, b = e^{md} sinh(Q)/Q
      if (small) {
        const C e = std::exp(md);
        a = e * (T(1) + q2d2 / T(2) * (T(1) + q2d2 / T(12) * (T(1) + q2d2 / T(30))));
        b = e * (T(1) + q2d2 / T(6) * (T(1) + q2d2 / T(20) * (T(1) + q2d2 / T(42))));
      } else {
        const C ep = std::exp(md + qd), em = std::exp(md - qd);
        a = T(0.5) * (ep + em);
        b = (ep - em) / (T(2) * qd);
      }
      s_out = b * d * n21;
      r_out = a + b * d * n11;
    } else {
      // t = tanh(Q)/Q; e^{md} / cosh Q = 2 / (e^{Q - md} + e^{-Q - md}).
      const C t =
          small ? T(1) - q2d2 / T(3) * (T(1) - T(2) * q2d2 / T(5) * (T(1) - T(17) * q2d2 / T(42))) : std::tanh(qd) / qd;
      const C denom = T(1) + t * d * n22;
      s_out = -t * d * n21 / denom;
      r_out = T(2) / (std::exp(qd - md) + std::exp(-qd - md)) / denom;
    }
  } else {
    const C s = n11 + q, w = p / s;
    const C lp = (m11 + w) * d, lm = (m22 - w) * d;
    const C two_q = T(2) * q;
    if (!r.reflection) {
      const C ep = std::exp(lp), em = std::exp(lm);
      s_out = n21 * (ep - em) / two_q;
      r_out = (s * ep + w * em) / two_q;
    } else if (std::real(qd) >= T(0)) {  // E+ dominant
      const C rho = std::exp(T(-2) * qd);
      const C den = w + s * rho;
      s_out = -n21 * (T(1) - rho) / den;
      r_out = two_q * std::exp(lm) / den;
    } else {  // E- dominant
      const C rho = std::exp(T(2) * qd);
      const C den = w * rho + s;
      s_out = -n21 * (rho - T(1)) / den;
      r_out = two_q * std::exp(lp) / den;
    }
  }
  r.efficiency = atMostOne(acs / c_r * std::norm(s_out));
  r.zero_order = atMostOne(std::norm(r_out));
  return r;
}

template <class T>
inline ResultT<T> evaluateT(T c_r, T c_s, T vartheta, T kappa, T alpha, T d) {
  return alpha > T(0) ? absorbingT<T>(c_r, c_s, vartheta, kappa, alpha, d) : losslessT<T>(c_r, c_s, vartheta, kappa, d);
}

inline Result lossless(double c_r, double c_s, double vartheta, double kappa, double d) {
  return losslessT<double>(c_r, c_s, vartheta, kappa, d);
}

// General film with mean amplitude absorption alpha (1/µm, >= 0). Exact solution of the
// coupled equations via the closed-form 2x2 matrix exponential; equals lossless() at alpha = 0.
Result absorbing(double c_r, double c_s, double vartheta, double kappa, double alpha, double d);

// Dispatch: the fast lossless path when alpha == 0.
inline Result evaluate(double c_r, double c_s, double vartheta, double kappa, double alpha, double d) {
  return alpha > 0.0 ? absorbing(c_r, c_s, vartheta, kappa, alpha, d) : lossless(c_r, c_s, vartheta, kappa, d);
}

}  // namespace fovea::kogelnik
