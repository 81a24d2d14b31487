#include "model/physics/kogelnik.h"

#include <complex>

namespace fovea::kogelnik {

namespace {
using C = std::complex<double>;
constexpr C kI{0.0, 1.0};
}  // namespace

// Write the coupled equations as y' = M y, y = (R, S):
//   M = [[-alpha/c_R, -i kappa/c_R], [-i kappa/c_S, -(alpha + i vartheta)/c_S]].
// With m = tr(M)/2 and N = M - m I (traceless, N^2 = q^2 I, q^2 = N11^2 + N12 N21):
//   exp(M d) = e^{m d} (cosh(Q) I + d sinh(Q)/Q N),  Q = q d,
// which is even in Q (the branch of the square root does not matter) and finite at Q = 0.
// Transmission: S(d) = T21, R(d) = T11. Reflection (S(d) = 0): S(0) = -T21/T22 and
// R(d) = det(T)/T22 = e^{2 m d}/T22. Exponentials are combined before they are formed, so
// thick or strongly absorbing films neither overflow nor produce inf/inf.
Result absorbing(double c_r, double c_s, double vartheta, double kappa, double alpha, double d) {
  Result r;
  r.reflection = c_s < 0.0;
  if (!(c_r > 0.0) || !(d > 0.0) || std::abs(c_s) < kGrazingCs) return r;
  const double acs = std::abs(c_s);
  r.nu = std::abs(kappa) * d / std::sqrt(c_r * acs);
  r.xi = std::abs(vartheta) * d / (2.0 * acs);

  const C m11 = -alpha / c_r;
  const C m22 = -(alpha + kI * vartheta) / c_s;
  const C n12 = -kI * kappa / c_r;
  const C n21 = -kI * kappa / c_s;
  const C md = 0.5 * (m11 + m22) * d;
  const C n11 = 0.5 * (m11 - m22);
  const C n22 = -n11;
  const C q2d2 = (n11 * n11 + n12 * n21) * (d * d);
  const C q = std::sqrt(q2d2);  // Q = q d
  const bool small = std::abs(q2d2) < 1e-6;

  if (!r.reflection) {
    C a, b;  // a = e^{md} cosh Q, b = e^{md} sinh(Q)/Q
    if (small) {
      const C e = std::exp(md);
      a = e * (1.0 + q2d2 / 2.0 + q2d2 * q2d2 / 24.0);
      b = e * (1.0 + q2d2 / 6.0 + q2d2 * q2d2 / 120.0);
    } else {
      const C ep = std::exp(md + q), em = std::exp(md - q);
      a = 0.5 * (ep + em);
      b = (ep - em) / (2.0 * q);
    }
    const C s_out = b * d * n21;
    const C r_out = a + b * d * n11;
    r.efficiency = acs / c_r * std::norm(s_out);
    r.zero_order = std::norm(r_out);
    return r;
  }

  // t = tanh(Q)/Q, bounded for large |Q| (glibc's ctanh saturates correctly).
  const C t = small ? 1.0 - q2d2 / 3.0 + 2.0 * q2d2 * q2d2 / 15.0 : std::tanh(q) / q;
  const C denom = 1.0 + t * d * n22;
  const C s0 = -t * d * n21 / denom;
  // e^{md} / cosh Q = 2 / (e^{Q - md} + e^{-Q - md})
  const C e_over_cosh = 2.0 / (std::exp(q - md) + std::exp(-q - md));
  const C r_out = e_over_cosh / denom;
  r.efficiency = acs / c_r * std::norm(s0);
  r.zero_order = std::norm(r_out);
  return r;
}

}  // namespace fovea::kogelnik
