// Vectorisable Kogelnik closed forms (see kogelnik_batch.h). Built with -O3 -fno-math-errno
// -fno-trapping-math (lets GCC if-convert the selects: the loop vectorises for AVX2/AVX-512)
// -ffp-contract=off (model/CMakeLists.txt): IEEE arithmetic, no reassociation, so every clone
// (AVX-512, AVX2, baseline) returns the same bits.
#include "model/physics/kogelnik_batch.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include "model/physics/kogelnik.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
#define FOVEA_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define FOVEA_CLONES
#endif

namespace fovea::kogelnik {

namespace {

// Constants of one floating type.
template <class T>
struct K;

template <>
struct K<double> {
  // pi/2 = kHalfPi1 + kHalfPi2 + kHalfPi3 (Cephes sin.c's pi/4 split, doubled): k * kHalfPi1 is exact for k < 2^29.
  static constexpr double kHalfPi1 = 1.57079625129699707031e+00, kHalfPi2 = 7.54978941586159635336e-08,
                          kHalfPi3 = 5.39030285815811905290e-15;
  static constexpr double two_over_pi = 6.36619772367581382433e-01;
  static constexpr double max_phase = 1e6;  // beyond: scalar path (reduction error would grow)
  // Cephes sin/cos on [-pi/4, pi/4]: sin r = r + r z sinPoly(z), cos r = 1 - z/2 + z^2 cosPoly(z), z = r^2.
  static double sinPoly(double z) {
    return ((((1.58962301576546568060e-10 * z - 2.50507477628578072866e-8) * z + 2.75573136213857245213e-6) * z -
             1.98412698295895385996e-4) *
                z +
            8.33333333332211858878e-3) *
               z -
           1.66666666666666307295e-1;
  }
  static double cosPoly(double z) {
    return ((((-1.13585365213876817300e-11 * z + 2.08757008419747316778e-9) * z - 2.75573141792967388112e-7) * z +
             2.48015872888517045348e-5) *
                z -
            1.38888888888730564116e-3) *
               z +
           4.16666666666665929218e-2;
  }
  // shc(a) = sum a^k / (2k+1)! for |a| < 1: first dropped term 1/25! < 1e-25.
  static double series(double a) {
    double p = 1.0 / 6402373705728000.0;  // 1/19!
    p = p * a + 1.0 / 355687428096000.0;  // 1/17!
    p = p * a + 1.0 / 1307674368000.0;    // 1/15!
    p = p * a + 1.0 / 6227020800.0;       // 1/13!
    p = p * a + 1.0 / 39916800.0;         // 1/11!
    p = p * a + 1.0 / 362880.0;           // 1/9!
    p = p * a + 1.0 / 5040.0;             // 1/7!
    p = p * a + 1.0 / 120.0;              // 1/5!
    p = p * a + 1.0 / 6.0;                // 1/3!
    return p * a + 1.0;
  }
  static constexpr double log2e = 1.44269504088896338700e+00;
  static constexpr double ln2_hi = 6.93147180369123816490e-01, ln2_lo = 1.90821492927058770002e-10;
  // e^r, |r| <= ln2/2: Taylor to r^13 (remainder < 1e-17 relative).
  static double expPoly(double r) {
    double p = 1.0 / 6227020800.0;  // 1/13!
    p = p * r + 1.0 / 479001600.0;
    p = p * r + 1.0 / 39916800.0;
    p = p * r + 1.0 / 3628800.0;
    p = p * r + 1.0 / 362880.0;
    p = p * r + 1.0 / 40320.0;
    p = p * r + 1.0 / 5040.0;
    p = p * r + 1.0 / 720.0;
    p = p * r + 1.0 / 120.0;
    p = p * r + 1.0 / 24.0;
    p = p * r + 1.0 / 6.0;
    p = p * r + 0.5;
    p = p * r + 1.0;
    return p * r + 1.0;
  }
};

template <>
struct K<float> {
  // Cephes sinf.c's pi/4 split, doubled: k * kHalfPi1 exact for k < 2^16.
  static constexpr float kHalfPi1 = 1.5703125f, kHalfPi2 = 4.837512969970703125e-4f, kHalfPi3 = 7.54978995489188216e-8f;
  static constexpr float two_over_pi = 0.636619772367581343f;
  static constexpr float max_phase = 8192.0f;
  static float sinPoly(float z) { return (-1.9515295891e-4f * z + 8.3321608736e-3f) * z - 1.6666654611e-1f; }
  static float cosPoly(float z) {
    return (2.443315711809948e-5f * z - 1.388731625493765e-3f) * z + 4.166664568298827e-2f;
  }
  static float series(float a) {
    float p = 1.0f / 6227020800.0f;  // 1/13!
    p = p * a + 1.0f / 39916800.0f;
    p = p * a + 1.0f / 362880.0f;
    p = p * a + 1.0f / 5040.0f;
    p = p * a + 1.0f / 120.0f;
    p = p * a + 1.0f / 6.0f;
    return p * a + 1.0f;
  }
  static constexpr float log2e = 1.44269504088896341f;
  static constexpr float ln2_hi = 0.693359375f, ln2_lo = -2.12194440e-4f;
  static float expPoly(float r) {
    float p = 1.0f / 5040.0f;
    p = p * r + 1.0f / 720.0f;
    p = p * r + 1.0f / 120.0f;
    p = p * r + 1.0f / 24.0f;
    p = p * r + 1.0f / 6.0f;
    p = p * r + 0.5f;
    p = p * r + 1.0f;
    return p * r + 1.0f;
  }
};

template <class T>
struct Element {
  T eta, zero;  // losslessT's efficiency and zero_order
};

// One element, branch-free (selects only), so the loop vectorises. Returns NaN when the phase
// is beyond the vector reduction's range: the caller finishes those with the scalar path.
template <class T>
inline Element<T> element(T c_r, T c_s, T vartheta, T kappa, T d) {
  using Kt = K<T>;
  const T acs = std::fabs(c_s);
  const bool valid = (c_r > T(0)) & (d > T(0)) & (acs >= T(kGrazingCs));
  const T nu = std::fabs(kappa) * d / std::sqrt(c_r * acs);
  const T xi = std::fabs(vartheta) * d / (T(2) * acs);
  const bool reflection = c_s < T(0);
  const T nu2 = nu * nu;
  const T a = reflection ? (nu - xi) * (nu + xi) : -(nu2 + xi * xi);
  const T aa = std::fabs(a);
  const T u = std::sqrt(aa);
  // sin(u)/u, u >= 1: Cody-Waite reduction by pi/2, quadrant select.
  const T k = std::rint(u * Kt::two_over_pi);
  const T r = ((u - k * Kt::kHalfPi1) - k * Kt::kHalfPi2) - k * Kt::kHalfPi3;
  const T z = r * r;
  const T s = r + r * z * Kt::sinPoly(z);
  const T c = T(1) - T(0.5) * z + z * z * Kt::cosPoly(z);
  // Quadrant q = k mod 4: sin(r + q pi/2) is s, c, -s, -c and cos(r + q pi/2) is c, -s, -c, s
  // for q = 0..3 (selects on doubles only, so the vectoriser can if-convert them).
  const T q = k - T(4) * std::floor(k * T(0.25));
  const T odd = q - T(2) * std::floor(q * T(0.5));
  const T sc = odd == T(0) ? s : c;
  const T sin_u = q >= T(2) ? -sc : sc;
  const T cs = odd == T(0) ? c : s;
  const T cos_u = (q > T(0.5)) & (q < T(2.5)) ? -cs : cs;
  // sinh(u)/u for 1 <= u <= 20 (beyond, reflection eta is 1 to rounding: g > 2e8).
  // Clamps by selects, not fmin/fmax (which GCC 12 does not vectorise); a NaN maps to 20 and 0
  // as fmin/fmax would map it, so the cast below stays defined.
  const T uc = u < T(20) ? u : T(20);
  const T n0 = std::rint(uc * Kt::log2e);
  const T n1 = n0 > T(0) ? n0 : T(0);
  const T n = n1 < T(29) ? n1 : T(29);
  const T rr = (uc - n * Kt::ln2_hi) - n * Kt::ln2_lo;
  const T e = Kt::expPoly(rr) * static_cast<T>(std::int32_t{1} << static_cast<std::int32_t>(n));
  const T sinh_u = T(0.5) * (e - T(1) / e);
  const T shc = aa < T(1) ? Kt::series(a) : (a < T(0) ? sin_u / u : sinh_u / uc);
  const T g = nu * shc;
  const T g2 = g * g;
  const bool saturated = a > T(400);  // u > 20: g^2 > 1e17 nu^2, eta = 1 and 1 / (1 + g^2) < 1e-17
  const T eta_r = saturated ? T(1) : T(1) / (T(1) + T(1) / g2);
  const T zero_r = saturated ? T(0) : T(1) / (T(1) + g2);
  const T eta_t = nu2 * shc * shc;
  // Transmission (a = -(nu^2 + xi^2) <= 0, so cosh(sqrt(a)) = cos u): |R(d)|^2 = cos^2 u +
  // xi^2 shc^2, the closed form of losslessT (kogelnik.h), clamped at 1 like it.
  const T zero_t0 = cos_u * cos_u + xi * xi * shc * shc;
  const T zero_t = zero_t0 < T(1) ? zero_t0 : T(1);
  const T eta = reflection ? eta_r : eta_t;
  const T zero = reflection ? zero_r : zero_t;
  const bool out_of_range = (a < T(0)) & (u > Kt::max_phase);
  const T nan = std::numeric_limits<T>::quiet_NaN();
  return {valid ? (out_of_range ? nan : eta) : T(0), valid ? (out_of_range ? nan : zero) : T(1)};
}

template <class T>
inline void finish(const T* c_r, const T* c_s, const T* vartheta, const T* kappa, const T* d, T* eta, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    if (std::isnan(eta[i])) eta[i] = losslessT<T>(c_r[i], c_s[i], vartheta[i], kappa[i], d[i]).efficiency;
}

FOVEA_CLONES
void batchDouble(const double* __restrict c_r, const double* __restrict c_s, const double* __restrict vartheta,
                 const double* __restrict kappa, const double* __restrict d, double* __restrict eta, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) eta[i] = element<double>(c_r[i], c_s[i], vartheta[i], kappa[i], d[i]).eta;
}

FOVEA_CLONES
void batchDoubleWithZero(const double* __restrict c_r, const double* __restrict c_s, const double* __restrict vartheta,
                         const double* __restrict kappa, const double* __restrict d, double* __restrict eta,
                         double* __restrict zero, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const Element<double> x = element<double>(c_r[i], c_s[i], vartheta[i], kappa[i], d[i]);
    eta[i] = x.eta;
    zero[i] = x.zero;
  }
}

FOVEA_CLONES
void batchFloat(const float* __restrict c_r, const float* __restrict c_s, const float* __restrict vartheta,
                const float* __restrict kappa, const float* __restrict d, float* __restrict eta, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) eta[i] = element<float>(c_r[i], c_s[i], vartheta[i], kappa[i], d[i]).eta;
}

}  // namespace

void losslessBatch(const double* c_r, const double* c_s, const double* vartheta, const double* kappa, const double* d,
                   double* eta, std::size_t n) {
  batchDouble(c_r, c_s, vartheta, kappa, d, eta, n);
  finish(c_r, c_s, vartheta, kappa, d, eta, n);
}

void losslessBatch(const double* c_r, const double* c_s, const double* vartheta, const double* kappa, const double* d,
                   double* eta, double* zero_order, std::size_t n) {
  batchDoubleWithZero(c_r, c_s, vartheta, kappa, d, eta, zero_order, n);
  for (std::size_t i = 0; i < n; ++i)
    if (std::isnan(eta[i])) {
      const ResultT<double> r = losslessT<double>(c_r[i], c_s[i], vartheta[i], kappa[i], d[i]);
      eta[i] = r.efficiency;
      zero_order[i] = r.zero_order;
    }
}

void losslessBatch(const float* c_r, const float* c_s, const float* vartheta, const float* kappa, const float* d,
                   float* eta, std::size_t n) {
  batchFloat(c_r, c_s, vartheta, kappa, d, eta, n);
  finish(c_r, c_s, vartheta, kappa, d, eta, n);
}

const char* batchInstructionSet() {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return "avx512f";
  if (__builtin_cpu_supports("avx2")) return "avx2";
  return "x86-64";
#else
  return "portable";
#endif
}

}  // namespace fovea::kogelnik
