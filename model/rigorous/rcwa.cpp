#include "model/rigorous/rcwa.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "model/rigorous/smatrix.h"
#include "model/units.h"

namespace fovea::rigorous {

namespace {

using cd = std::complex<double>;
using Eigen::Index;
using Eigen::MatrixXcd;
using Eigen::VectorXcd;

// z-wavenumber (/k0) of a mode with γ² = g2: the root that decays or propagates towards +z
// (Im γ > 0, or Im γ = 0 and Re γ ≥ 0). A root at exactly zero (an order grazing inside a layer,
// the Rayleigh anomaly) gets a vanishing loss so that the mode matrices stay invertible.
cd forwardRoot(cd g2) {
  cd g = std::sqrt(g2);
  if (g.imag() < 0.0 || (g.imag() == 0.0 && g.real() < 0.0)) g = -g;
  if (std::abs(g) < 1e-9) g = cd(0.0, 1e-9);
  return g;
}

// Everything about the film that does not depend on the slice: harmonics of ε and 1/ε of the
// z = 0 profile, tangential wave vectors, reference (gap) admittance.
struct FilmSetup {
  int n_orders = 0;                           // N
  Index size = 1;                             // 2N+1
  VectorXcd kx;                               // k_x,m / k0, m = −N … N
  double kx_grating = 0.0, kz_grating = 0.0;  // K_x/k0, K_z/k0
  double k0_um = 0.0;                         // 2π/λ in 1/µm
  bool te = true;
  bool uniform_x = false;  // K_x = 0
  cd gap_admittance;       // V of the zero-thickness gap medium (W_gap = I)
};

// Permittivity at fringe phase u = K·r: (n0 + n1 cos u)², or Kogelnik's linearised
// n0² + 2 n0 n1 cos u when asked (diagnostic: separates the two-wave error from the O(n1²) terms).
cd localPermittivity(const RcwaProblem& p, double u) {
  if (p.linearised_permittivity) return p.n0 * p.n0 + 2.0 * p.n0 * p.n1 * std::cos(u);
  const cd n = p.n0 + p.n1 * std::cos(u);
  return n * n;
}

// Fourier coefficients c_h, |h| ≤ hmax, of 1/ε(u) by the trapezoidal rule, which
// converges geometrically for this analytic periodic function (ratio ≈ n1/(2 n0) per harmonic).
std::vector<cd> inversePermittivityHarmonics(const RcwaProblem& p, int hmax) {
  const int samples = 4 * hmax + 64;
  std::vector<cd> c(2 * hmax + 1, cd(0.0));
  std::vector<cd> f(samples);
  for (int k = 0; k < samples; ++k) {
    const double u = 2.0 * kPi * k / samples;
    f[k] = 1.0 / localPermittivity(p, u);
  }
  for (int h = -hmax; h <= hmax; ++h) {
    cd s(0.0);
    for (int k = 0; k < samples; ++k) s += f[k] * std::polar(1.0, -2.0 * kPi * h * k / samples);
    c[h + hmax] = s / double(samples);
  }
  return c;
}

// Toeplitz matrix T_mn = c_{n−m} e^{i (n−m) K_z z} (order m has k_x = k_x,inc − m K_x, so the
// harmonic e^{i h K·r} of the profile couples order n into order m = n − h).
MatrixXcd toeplitz(const std::vector<cd>& c, int hmax, Index size, double kz_times_z) {
  MatrixXcd t = MatrixXcd::Zero(size, size);
  for (Index m = 0; m < size; ++m)
    for (Index n = 0; n < size; ++n) {
      const int h = int(n - m);
      if (std::abs(h) > hmax) continue;
      t(m, n) = c[h + hmax] * std::polar(1.0, h * kz_times_z);
    }
  return t;
}

// S-matrix (gap basis) of one homogeneous-in-z slab of thickness dz_um whose profile is the film
// profile at height z_um: eigenmodes of the RCWA system, then Rumpf's symmetric-layer formulas.
SMatrix sliceSMatrix(const FilmSetup& s, const RcwaProblem& p, double z_um, double dz_um) {
  const Index n = s.size;
  const int hmax = std::max(2, 2 * s.n_orders);
  const cd n0 = p.n0;
  const double n1 = p.n1;
  // ε harmonics of (n0 + n1 cos u)²: exact, |h| ≤ 2.
  std::vector<cd> eps(2 * hmax + 1, cd(0.0));
  eps[hmax] = n0 * n0 + 0.5 * n1 * n1;
  eps[hmax - 1] = eps[hmax + 1] = n0 * n1;
  eps[hmax - 2] = eps[hmax + 2] = 0.25 * n1 * n1;
  if (p.linearised_permittivity) {
    eps[hmax] = n0 * n0;
    eps[hmax - 2] = eps[hmax + 2] = 0.0;
  }
  const double phase = s.kz_grating * s.k0_um * z_um;
  // K_x = 0: every harmonic of the profile lands on the single order, i.e. the slice is the
  // homogeneous medium ε(z) (its own 1/ε exactly, no factorisation question).
  const cd eps_local = localPermittivity(p, phase);
  const MatrixXcd E = s.uniform_x ? MatrixXcd::Constant(1, 1, eps_local) : toeplitz(eps, hmax, n, phase);
  const auto kxd = s.kx.asDiagonal();

  MatrixXcd a, finv, f;
  if (s.te) {
    a = E;
    a.diagonal() -= s.kx.cwiseAbs2().cast<cd>();  // TE: γ² from E − Kx² (kx real)
  } else {
    // TM with Li's rules: A = [[1/ε]]^{-1} (I − Kx [[ε]]^{-1} Kx).
    if (s.uniform_x) {
      f = MatrixXcd::Constant(1, 1, 1.0 / eps_local);
    } else {
      const std::vector<cd> inv = inversePermittivityHarmonics(p, hmax);
      f = toeplitz(inv, hmax, n, phase);
    }
    finv = f.partialPivLu().inverse();
    const MatrixXcd einvkx = E.partialPivLu().solve(MatrixXcd(kxd));
    a = finv * (MatrixXcd::Identity(n, n) - kxd * einvkx);
  }
  Eigen::ComplexEigenSolver<MatrixXcd> es(a, true);
  if (es.info() != Eigen::Success) throw std::runtime_error("RCWA: eigen-decomposition failed");
  const MatrixXcd& w = es.eigenvectors();
  VectorXcd gamma(n);
  for (Index i = 0; i < n; ++i) gamma(i) = forwardRoot(es.eigenvalues()(i));

  const MatrixXcd winv = w.partialPivLu().inverse();
  // V^{-1}: TE V = −W γ; TM V = [[1/ε]] W γ.
  MatrixXcd vinv = gamma.cwiseInverse().asDiagonal() * winv;
  if (s.te)
    vinv = -vinv;
  else
    vinv = vinv * finv;
  const MatrixXcd A = winv + vinv * s.gap_admittance;
  const MatrixXcd B = winv - vinv * s.gap_admittance;
  VectorXcd x(n);
  for (Index i = 0; i < n; ++i) x(i) = std::exp(cd(0.0, 1.0) * gamma(i) * (s.k0_um * dz_um));
  const auto X = x.asDiagonal();
  const Eigen::PartialPivLU<MatrixXcd> alu(A);
  const MatrixXcd ainvxb = alu.solve(X * B);
  const MatrixXcd xb = X * B;
  const Eigen::PartialPivLU<MatrixXcd> dlu(A - xb * ainvxb);  // A − X B A^{-1} X B
  SMatrix sm;
  sm.s11 = dlu.solve(xb * alu.solve(X * A) - B);
  sm.s12 = dlu.solve(X * (A - B * alu.solve(B)));
  sm.s21 = sm.s12;
  sm.s22 = sm.s11;
  return sm;
}

// Admittance V (the tangential magnetic/electric partner of the mode amplitude) of the forward
// plane waves of a homogeneous outer medium.
VectorXcd outerAdmittance(const FilmSetup& s, double n_medium, VectorXcd* gamma_out) {
  VectorXcd g(s.size), v(s.size);
  const double eps = n_medium * n_medium;
  for (Index i = 0; i < s.size; ++i) {
    g(i) = forwardRoot(cd(eps) - s.kx(i) * s.kx(i));
    v(i) = s.te ? -g(i) : g(i) / eps;
  }
  if (gamma_out) *gamma_out = g;
  return v;
}

// Semi-infinite cover on port 1 (its amplitudes: incident a1, reflected b1), gap on port 2.
SMatrix coverSMatrix(const VectorXcd& v_cover, cd v_gap) {
  const VectorXcd a = VectorXcd::Ones(v_cover.size()) + v_cover / v_gap;
  const VectorXcd b = VectorXcd::Ones(v_cover.size()) - v_cover / v_gap;
  SMatrix s;
  s.s11 = (-(b.cwiseQuotient(a))).asDiagonal();
  s.s12 = (2.0 * a.cwiseInverse()).asDiagonal();
  s.s21 = (0.5 * (a - b.cwiseProduct(b).cwiseQuotient(a))).asDiagonal();
  s.s22 = b.cwiseQuotient(a).asDiagonal();
  return s;
}

// Gap on port 1, semi-infinite substrate on port 2.
SMatrix substrateSMatrix(const VectorXcd& v_sub, cd v_gap) {
  const VectorXcd a = VectorXcd::Ones(v_sub.size()) + v_sub / v_gap;
  const VectorXcd b = VectorXcd::Ones(v_sub.size()) - v_sub / v_gap;
  SMatrix s;
  s.s11 = b.cwiseQuotient(a).asDiagonal();
  s.s12 = (0.5 * (a - b.cwiseProduct(b).cwiseQuotient(a))).asDiagonal();
  s.s21 = (2.0 * a.cwiseInverse()).asDiagonal();
  s.s22 = (-(b.cwiseQuotient(a))).asDiagonal();
  return s;
}

// 1-D stack (K_x = 0): scalar S-matrices, the same formulas as sliceSMatrix/starProduct with
// 1×1 blocks (W = 1; TE V = −γ, TM V = γ/ε; gap V_g = ∓1), without dynamic-matrix overhead.
struct ScalarS {
  cd s11{0.0}, s12{1.0}, s21{1.0}, s22{0.0};
};
ScalarS scalarStar(const ScalarS& a, const ScalarS& b) {
  const cd den = 1.0 - b.s11 * a.s22;
  return {a.s11 + a.s12 * b.s11 * a.s21 / den, a.s12 * b.s12 / den, b.s21 * a.s21 / den,
          b.s22 + b.s21 * a.s22 * b.s12 / den};
}
ScalarS scalarSlice(const FilmSetup& s, cd eps, double dz_um) {
  const cd kx = s.kx(0);
  const cd g = forwardRoot(eps - kx * kx);
  const cd vinv_vg = s.te ? 1.0 / g : eps / g;  // V^{-1} V_gap
  const cd A = 1.0 + vinv_vg, B = 1.0 - vinv_vg;
  const cd X = std::exp(cd(0.0, 1.0) * g * (s.k0_um * dz_um));
  const cd den = A - X * B / A * X * B;
  const cd s11 = (X * B / A * X * A - B) / den;
  const cd s12 = X * (A - B / A * B) / den;
  return {s11, s12, s12, s11};
}

VectorXcd shiftPhases(const FilmSetup& s, double z_um) {
  VectorXcd d(s.size);
  for (Index i = 0; i < s.size; ++i) {
    const int m = int(i) - s.n_orders;
    d(i) = std::polar(1.0, -m * s.kz_grating * s.k0_um * z_um);
  }
  return d;
}

void requireFinite(double v, const char* name) {
  if (!std::isfinite(v)) throw std::invalid_argument(std::string("RCWA: ") + name + " is not finite");
}

void validate(const RcwaProblem& p, const RcwaOptions& o) {
  requireFinite(p.n0.real(), "n0");
  requireFinite(p.n0.imag(), "n0 (imaginary part)");
  requireFinite(p.n1, "n1");
  requireFinite(p.thickness_um, "thickness_um");
  requireFinite(p.period_nm, "period_nm");
  requireFinite(p.slant_deg, "slant_deg");
  requireFinite(p.wavelength_nm, "wavelength_nm");
  requireFinite(p.n_cover, "n_cover");
  requireFinite(p.n_substrate, "n_substrate");
  requireFinite(p.kx_over_k0, "incidence (kx_over_k0)");
  if (p.n0.real() <= 0.0) throw std::invalid_argument("RCWA: n0 must have a positive real part");
  if (p.n0.imag() < 0.0) throw std::invalid_argument("RCWA: n0 must have Im n0 >= 0 (gain is not supported)");
  if (p.thickness_um < 0.0) throw std::invalid_argument("RCWA: thickness_um must be >= 0");
  if (p.period_nm <= 0.0) throw std::invalid_argument("RCWA: period_nm must be > 0");
  if (p.wavelength_nm <= 0.0) throw std::invalid_argument("RCWA: wavelength_nm must be > 0");
  if (p.n_cover <= 0.0) throw std::invalid_argument("RCWA: n_cover must be > 0");
  if (p.n_substrate <= 0.0) throw std::invalid_argument("RCWA: n_substrate must be > 0");
  if (std::abs(p.kx_over_k0) >= p.n_cover)
    throw std::invalid_argument("RCWA: the incident wave cannot propagate in the cover (|n sin θ| >= n_cover)");
  if (o.orders < 0 || o.orders > 400) throw std::invalid_argument("RCWA: orders must be in [0, 400]");
  if (o.slices < 1) throw std::invalid_argument("RCWA: slices must be >= 1");
}

}  // namespace

void RcwaProblem::setCoverAngleDeg(double deg) {
  kx_over_k0 = n_cover * std::sin(degToRad(deg));
}
void RcwaProblem::setFilmAngleDeg(double deg) {
  kx_over_k0 = n0.real() * std::sin(degToRad(deg));
}

const RcwaOrder* RcwaResult::find(int m, bool reflected_side) const {
  for (const RcwaOrder& o : orders)
    if (o.order == m && o.reflected == reflected_side) return &o;
  return nullptr;
}
double RcwaResult::efficiency(int m, bool reflected_side) const {
  const RcwaOrder* o = find(m, reflected_side);
  return o ? o->efficiency : 0.0;
}

RcwaResult solveRcwa(const RcwaProblem& p, const RcwaOptions& o) {
  validate(p, o);
  const double slant = p.slant_deg * kPi / 180.0;
  const double k_ratio = p.wavelength_nm / p.period_nm;  // K/k0
  double kxg = k_ratio * std::sin(slant), kzg = k_ratio * std::cos(slant);
  if (std::abs(kxg) < 1e-12 * k_ratio) kxg = 0.0;
  if (std::abs(kzg) < 1e-12 * k_ratio) kzg = 0.0;
  const bool uniform_x = kxg == 0.0;  // 1-D multilayer: only order 0 exists
  const bool invariant_z = kzg == 0.0 || p.n1 == 0.0;
  const bool thin = p.thickness_um == 0.0;

  FilmSetup s;
  s.n_orders = uniform_x ? 0 : o.orders;
  s.size = 2 * s.n_orders + 1;
  s.kx_grating = kxg;
  s.kz_grating = kzg;
  s.k0_um = 2.0 * kPi / (p.wavelength_nm * 1e-3);
  s.te = p.polarization == RcwaPolarization::TE;
  s.uniform_x = uniform_x;
  s.gap_admittance = s.te ? cd(-1.0) : cd(1.0);
  s.kx.resize(s.size);
  for (Index i = 0; i < s.size; ++i) s.kx(i) = p.kx_over_k0 - double(int(i) - s.n_orders) * kxg;

  const int slices = (invariant_z || thin) ? 1 : o.slices;
  const double dz = p.thickness_um / slices;
  SMatrix film = SMatrix::identity(s.size);
  if (thin) {
    // zero thickness: nothing between cover and substrate
  } else if (invariant_z) {
    film = sliceSMatrix(s, p, 0.0, p.thickness_um);
  } else if (uniform_x) {
    ScalarS acc;
    for (int j = 0; j < slices; ++j) {
      const double u = s.kz_grating * s.k0_um * (j + 0.5) * dz;
      acc = scalarStar(acc, scalarSlice(s, localPermittivity(p, u), dz));
    }
    film.s11(0, 0) = acc.s11;
    film.s12(0, 0) = acc.s12;
    film.s21(0, 0) = acc.s21;
    film.s22(0, 0) = acc.s22;
  } else if (o.explicit_slices) {
    for (int j = 0; j < slices; ++j) film = starProduct(film, sliceSMatrix(s, p, (j + 0.5) * dz, dz));
  } else {
    // One decomposition, D-conjugates for the other slices, stack assembled by doubling:
    // block = slices [0, b), appended at offset o as D(o dz) block D(o dz)^{-1}.
    SMatrix block = conjugated(sliceSMatrix(s, p, 0.0, dz), shiftPhases(s, 0.5 * dz));
    long long b = 1, offset = 0;
    for (long long rest = slices; rest > 0; rest >>= 1) {
      if (rest & 1) {
        film = starProduct(film, conjugated(block, shiftPhases(s, double(offset) * dz)));
        offset += b;
      }
      if (rest > 1) {
        block = starProduct(block, conjugated(block, shiftPhases(s, double(b) * dz)));
        b *= 2;
      }
    }
  }

  VectorXcd g_cover, g_sub;
  const VectorXcd v_cover = outerAdmittance(s, p.n_cover, &g_cover);
  const VectorXcd v_sub = outerAdmittance(s, p.n_substrate, &g_sub);
  const SMatrix total = starProduct(starProduct(coverSMatrix(v_cover, s.gap_admittance), film),
                                    substrateSMatrix(v_sub, s.gap_admittance));

  const Index inc = s.n_orders;  // index of order 0
  const VectorXcd r = total.s11.col(inc);
  const VectorXcd t = total.s21.col(inc);
  // Power flux along z: TE |u|² Re γ, TM |u|² Re(γ/ε) (u = E_y resp. Z0 H_y).
  const double eps_c = p.n_cover * p.n_cover, eps_s = p.n_substrate * p.n_substrate;
  const double flux_in = s.te ? g_cover(inc).real() : g_cover(inc).real() / eps_c;

  RcwaResult res;
  res.orders_used = s.n_orders;
  res.slices_used = slices;
  res.z_invariant = invariant_z;
  res.laterally_uniform = uniform_x;
  auto angle = [](double kx, double kz) { return radToDeg(std::atan2(kx, kz)); };
  for (Index i = 0; i < s.size; ++i) {
    const double kx = s.kx(i).real();
    if (kx * kx < eps_c) {
      const double gz = g_cover(i).real();
      const double flux = s.te ? gz : gz / eps_c;
      res.orders.push_back({int(i) - s.n_orders, true, std::norm(r(i)) * flux / flux_in, angle(kx, -gz)});
    }
  }
  for (Index i = 0; i < s.size; ++i) {
    const double kx = s.kx(i).real();
    if (kx * kx < eps_s) {
      const double gz = g_sub(i).real();
      const double flux = s.te ? gz : gz / eps_s;
      res.orders.push_back({int(i) - s.n_orders, false, std::norm(t(i)) * flux / flux_in, angle(kx, gz)});
    }
  }
  for (const RcwaOrder& ord : res.orders)
    (ord.reflected ? res.reflected_total : res.transmitted_total) += ord.efficiency;
  res.total_efficiency = res.reflected_total + res.transmitted_total;
  return res;
}

KogelnikOrder kogelnikDiffractedOrder(const RcwaProblem& p) {
  const double slant = p.slant_deg * kPi / 180.0;
  const double k_ratio = p.wavelength_nm / p.period_nm;
  const double kxg = k_ratio * std::sin(slant), kzg = k_ratio * std::cos(slant);
  if (std::abs(kxg) < 1e-12 * k_ratio) return {0, true};
  const double n = p.n0.real();
  const double kz_inc = std::sqrt(std::max(0.0, n * n - p.kx_over_k0 * p.kx_over_k0));
  return {1, kz_inc - kzg < 0.0};
}

RcwaConvergedResult solveRcwaConverged(const RcwaProblem& problem, const RcwaConvergence& c) {
  if (!(c.tolerance > 0.0)) throw std::invalid_argument("RCWA: convergence tolerance must be > 0");
  RcwaConvergedResult out;
  RcwaOptions opt;
  opt.orders = std::max(0, c.min_orders);
  opt.slices = std::max(1, c.min_slices);
  auto run = [&](const RcwaOptions& o) {
    ++out.solves;
    const RcwaResult r = solveRcwa(problem, o);
    return std::pair{r, r.efficiency(c.target_order, c.target_reflected)};
  };
  auto [res, eta] = run(opt);
  const bool slices_matter = !res.z_invariant && problem.thickness_um > 0.0;
  const bool orders_matter = !res.laterally_uniform;
  bool slices_ok = !slices_matter, orders_ok = !orders_matter;
  double change = 0.0;
  // Alternate: refine slices until stable, then orders until stable; a refinement of orders
  // re-opens the slice check (the staircase error depends weakly on N) and vice versa.
  for (int guard = 0; guard < 64 && !(slices_ok && orders_ok); ++guard) {
    RcwaOptions next = opt;
    const bool refine_slices = !slices_ok;
    if (refine_slices) {
      if (opt.slices >= c.max_slices) break;
      next.slices = std::min(c.max_slices, opt.slices * 2);
    } else {
      if (opt.orders >= c.max_orders) break;
      next.orders = std::min(c.max_orders, opt.orders + std::max(2, opt.orders / 2));
    }
    auto [r2, eta2] = run(next);
    change = std::abs(eta2 - eta);
    const bool stable = change < c.tolerance;
    opt = next;
    res = r2;
    eta = eta2;
    if (refine_slices) {
      slices_ok = stable;
    } else {
      orders_ok = stable;
      if (!stable && slices_matter) slices_ok = false;
    }
  }
  out.result = res;
  out.orders = res.orders_used;
  out.slices = res.slices_used;
  out.last_change = change;
  out.converged = slices_ok && orders_ok;
  return out;
}

}  // namespace fovea::rigorous
