#pragma once
// Rigorous coupled-wave analysis (RCWA) of a slanted sinusoidal volume grating: the exact
// (up to truncation and slicing) reference against which Kogelnik's two-wave theory is checked.
//
// Geometry (same frame as Kogelnik's planar model, model/physics): x along the film, z the film
// normal. Cover (incidence medium, real index n_cover) for z < 0, film 0 < z < d, substrate
// (real index n_substrate) for z > d. Inside the film the index is
//     n(x, z) = n0 + n1 cos(K·r),   K = (2π/Λ) (sin φ, 0, cos φ),
// φ = slant (angle of K from the film normal): 90° = unslanted transmission grating, 0° =
// unslanted reflection grating. n0 may be complex (absorption: Im n0 > 0, time dependence
// e^{-iωt}). We keep the INDEX form (Kogelnik's n1 is an index amplitude), so the permittivity
//     ε = (n0 + n1 cos K·r)² = n0² + n1²/2 + 2 n0 n1 cos K·r + (n1²/2) cos 2K·r
// has the exact Fourier harmonics ε_0 = n0² + n1²/2, ε_±1 = n0 n1, ε_±2 = n1²/4. The
// linearised n0² + 2 n0 n1 cos K·r would drop the mean-index shift n1²/(4 n0) and the second
// harmonic; both are O(n1²) and matter only for strong gratings, which is where RCWA is needed.
//
// Method: Moharam, Grann, Pommet & Gaylord, JOSA A 12, 1068 and 1077 (1995) (stable
// formulation), with Li's factorisation rules (JOSA A 13, 1870 (1996)) for TM: the ε E_x
// product uses the inverse rule [[1/ε]]^{-1}, the E_z = D_z/ε product the Laurent rule
// [[ε]]^{-1}. Thickness is handled by scattering matrices and the Redheffer star product
// (Li, JOSA A 13, 1024 (1996); the layer S-matrix in a zero-thickness gap basis as in Rumpf,
// PIER B 35, 241 (2011)): every exponential is exp(iγΔz) with Im γ ≥ 0, so nothing grows and
// films of any thickness (1 mm and more) are stable.
//
// Slanted fringes are sliced into M layers of equal thickness, layer j sampled at its middle
// z_j = (j + ½) d/M. A slanted sinusoid at height z is the z = 0 profile shifted along x, so the
// Toeplitz matrices of layer j are D_j E_0 D_j^{-1} with D_j = diag(exp(-i m K_z z_j)): one
// eigen-decomposition serves every layer, the layer S-matrices are D-conjugates of one another,
// and the stack of M layers is assembled by repeated doubling in O(log M) star products. So
// slicing costs almost nothing and the staircase error (∝ (K_z d/M)²) can be driven to zero.
// When K_x = 0 (unslanted reflection grating) the film is a 1-D stack: only the zeroth order
// exists and every slice is its own homogeneous layer (O(M) scalar star products).
//
// Orders: order m has tangential wave vector k_x,m = k_x,inc − m K_x, so m = +1 is the wave that
// Kogelnik calls diffracted (σ = ρ − K). Retained orders: m = −N … N.

#include <complex>
#include <cstdint>
#include <string>
#include <vector>

namespace fovea::rigorous {

enum class RcwaPolarization { TE, TM };  // TE = s (E along y), TM = p (H along y)

struct RcwaProblem {
  std::complex<double> n0{1.5, 0.0};  // mean film index (Im > 0: absorbing)
  double n1 = 0.0;                    // index modulation amplitude
  double thickness_um = 10.0;
  double period_nm = 500.0;      // fringe period Λ (along K)
  double slant_deg = 90.0;       // angle of K from the film normal
  double wavelength_nm = 532.0;  // vacuum wavelength
  double n_cover = 1.5;          // incidence medium (real)
  double n_substrate = 1.5;      // exit medium (real)
  double kx_over_k0 = 0.0;       // tangential wave vector of the incident wave / k0
  RcwaPolarization polarization = RcwaPolarization::TE;
  // Diagnostic: use Kogelnik's linearised ε = n0² + 2 n0 n1 cos K·r instead of (n0 + n1 cos)²,
  // to separate the two-wave error of Kogelnik's theory from its dropped O(n1²) terms.
  bool linearised_permittivity = false;

  // Incidence from the angle in the cover, or from the angle inside the film (Re n0), which is
  // what Kogelnik's probe angle is. Both just set kx_over_k0 (Snell's law: k_x is conserved).
  void setCoverAngleDeg(double deg);
  void setFilmAngleDeg(double deg);
};

struct RcwaOptions {
  int orders = 10;               // N: orders −N … N are retained (2N+1 harmonics)
  int slices = 64;               // M: layers of the staircase (ignored when K_z = 0)
  bool explicit_slices = false;  // build every layer separately (slow reference path, for tests)
};

struct RcwaOrder {
  int order = 0;
  bool reflected = false;   // true: back into the cover, false: into the substrate
  double efficiency = 0.0;  // fraction of incident power (z-component of the Poynting flux)
  double angle_deg = 0.0;   // wave vector in the outer medium from the +z normal, signed in
                            // the x–z plane, (−180, 180]: reflected orders have |angle| > 90
};

struct RcwaResult {
  std::vector<RcwaOrder> orders;  // every PROPAGATING reflected and transmitted order, reflected first
  double total_efficiency = 0.0;  // sum over all of them (1 for a lossless grating)
  double reflected_total = 0.0;
  double transmitted_total = 0.0;
  int orders_used = 0;             // N
  int slices_used = 0;             // M (1 when the film is z-invariant)
  bool z_invariant = false;        // K_z = 0: one layer is exact
  bool laterally_uniform = false;  // K_x = 0: a 1-D multilayer

  // Efficiency of order m on the given side (0 when it is evanescent or not retained).
  double efficiency(int m, bool reflected) const;
  const RcwaOrder* find(int m, bool reflected) const;
};

// Throws std::invalid_argument naming the bad field (non-finite values, thickness < 0,
// period ≤ 0, wavelength ≤ 0, cover/substrate index ≤ 0, incidence evanescent in the cover,
// orders < 0, slices < 1, Im n0 < 0).
RcwaResult solveRcwa(const RcwaProblem& problem, const RcwaOptions& options = {});

// The wave Kogelnik calls diffracted (σ = ρ − K) in RCWA's terms: order +1, on the reflected side
// when its z-component inside the film, k_z,inc − K_z, is negative (Kogelnik's c_S < 0); order 0
// reflected when K_x = 0 (the unslanted reflection grating is a 1-D stack).
struct KogelnikOrder {
  int order = 1;
  bool reflected = false;
};
KogelnikOrder kogelnikDiffractedOrder(const RcwaProblem& problem);

// Picks orders and slices for a requested accuracy: doubles the slices, then raises the orders,
// until the efficiency of the target order (m, side) changes by less than `tolerance` (absolute)
// between successive refinements, and the last refinement of the other parameter also held.
struct RcwaConvergence {
  double tolerance = 1e-4;
  int target_order = 1;
  bool target_reflected = false;  // (see kogelnikDiffractedOrder for Kogelnik's wave)
  int min_orders = 2, max_orders = 60;
  int min_slices = 8, max_slices = 1 << 22;  // doubling makes 4 M slices cost ~22 star products
};
struct RcwaConvergedResult {
  RcwaResult result;
  int orders = 0, slices = 0;
  double last_change = 0.0;  // |Δη| of the last refinement (≤ tolerance when converged)
  bool converged = false;
  int solves = 0;  // RCWA solves it took
};
RcwaConvergedResult solveRcwaConverged(const RcwaProblem& problem, const RcwaConvergence& convergence = {});

}  // namespace fovea::rigorous
