#pragma once
// One planar volume grating met by one probe, as both models of the Kogelnik-vs-RCWA comparison
// see it (Kogelnik's angles; inside-the-film probe angle), and Kogelnik's lossless closed forms
// for it: the textbook reference the rigorous model is compared with (the studio's full
// Kogelnik model, model/physics, must agree with them for lossless planar cases).

#include "model/rigorous/rcwa.h"

namespace fovea::rigorous {

struct PlanarCase {
  double n0 = 1.5, n1 = 0.0;
  double thickness_um = 10.0, period_nm = 500.0;
  double slant_deg = 90.0;  // φ: angle of K from the film normal
  double probe_deg = 0.0;   // θ: probe angle inside the film
  double wavelength_nm = 532.0;
  bool te = true;  // s (TE) or p (TM)
};

struct KogelnikEvaluation {
  double efficiency = 0.0, nu = 0.0, xi = 0.0;
  bool reflection = false;
};

// Kogelnik (Bell Syst. Tech. J. 48, 2909 (1969)), lossless:
//   c_R = cos θ, c_S = cos θ − (λ/(n0 Λ)) cos φ, ϑ = K cos(φ − θ) − K² λ/(4π n0),
//   ν = π n1 d (ρ̂·σ̂ for p)/(λ √|c_R c_S|), ξ = ϑ d/(2 |c_S|);
//   transmission (c_S > 0): η = sin²√(ν²+ξ²)/(1 + ξ²/ν²)                        (Eq. 43)
//   reflection   (c_S < 0): η = 1/(1 + (1 − ξ²/ν²)/sinh²√(ν²−ξ²))             (Eq. 56)
// (sinh(i s)² = −sin² s continues the reflection branch past ξ = ν.)
KogelnikEvaluation kogelnikClosedForm(const PlanarCase& c);

// The same case as an RCWA problem with index-matched cover and substrate (n_c = n_s = n0), so
// that the film's faces do not reflect and the inside angle is the outside angle.
RcwaProblem rcwaProblemOf(const PlanarCase& c);

// Kogelnik's dephasing ξ (geometry only; n1 does not enter) and the validity parameters:
// ρ = λ²/(Λ² n0 n1) (Moharam & Gaylord: Bragg regime for ρ ≳ 10) and Klein's
// Q = 2π λ d/(n0 Λ²).
double kogelnikXi(const PlanarCase& c);
double rhoParameter(const PlanarCase& c);
double kleinQ(const PlanarCase& c);

}  // namespace fovea::rigorous
