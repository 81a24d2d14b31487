#pragma once
// Second-order transfer of a wave through a recorded hologram at one plate point: the
// astigmatism of an off-axis HOE (issue 29).
//
// Derivation (first principles, the phase of the recorded fringes). Write each wave near the
// plate as exp(-i k psi) with psi its optical path (Siegman, "Lasers", ch. 16-17: a Gaussian
// beam along u is psi = z + x^T Q^-1 x / 2 over the plane normal to u, Q^-1 = 1/R - i lambda /
// (pi w^2) per principal section). A spherical wave diverging from a point at distance L along u
// has the 3-D Hessian of psi (I - u u^T)/L, one converging to a point -(I - u u^T)/L. The
// recorded fringes hold the phase k_rec (psi_signal - psi_reference); replayed at lambda the
// first order leaves with
//     psi_out = psi_in + mu (psi_signal - psi_reference),   mu = lambda / lambda_rec,
// on the plate. Its gradient along the plate is the grating equation (lateral_colour.h); its
// Hessian along the plate (E = [plate x, plate y], 3x2) is
//     H_out = E^T Q_in^-1 E - mu (E^T P_s E / L_s + E^T P_r E / L_r),   P_v = I - v v^T,
// (the input beam's Q_in^-1 here isotropic: E^T (I - u_in u_in^T) E / q_in). The outgoing
// wave along u_out has its own transverse matrix M (basis B, 3x2, normal to u_out) with
// E^T B M B^T E = H_out, so M = T^-T H_out T^-1, T = B^T E. When the waves lie in one plane of
// incidence (angles theta to the normal) the two sections separate and this is the holographic
// form of Coddington's equations (Welford, "Aberrations of Optical Systems", Adam Hilger 1986,
// the chapter on holographic optical elements; Latta, Appl. Opt. 10, 599 (1971)):
//     tangential  cos^2 theta_o / q'_t = cos^2 theta_i / q_t - mu (cos^2 theta_s / L_s + cos^2 theta_r / L_r)
//     sagittal              1 / q'_s  =            1 / q_s - mu (1 / L_s + 1 / L_r)
// (signal converging to its point, reference diverging from its point: the supplement's
// recording, phase_conjugate or not, stores the same fringes). The sagittal power is the thin
// lens the line-of-sight model used before; the tangential one differs unless all the waves
// meet the plate along its normal (an on-axis hologram: no astigmatism), and at mu = 1 a point
// source at the reference point is imaged stigmatically on the signal point, at any obliquity.
// Air on both sides of the plate (the prototype's cover and substrate indices are 1).

#include <complex>

#include <Eigen/Core>

namespace fovea {

struct HologramPointGeometry {
  Eigen::Vector3d plate_x = Eigen::Vector3d::UnitX(), plate_y = Eigen::Vector3d::UnitY();  // unit, in the plate
  Eigen::Vector3d point = Eigen::Vector3d::Zero();         // where the fringes were recorded (nominal pose)
  Eigen::Vector3d reference_mm = Eigen::Vector3d::Zero();  // recording reference point (diverging)
  Eigen::Vector3d signal_mm = Eigen::Vector3d::Zero();     // recording signal point (converging)
  double mu = 1.0;                                         // lambda / lambda_rec
};

// Direction of the first diffracted order (grating equation, tangential parts) for a probe
// along unit u_in, leaving to the side of `eye_side` (a vector pointing from the plate to the
// eye). Zero vector if evanescent.
Eigen::Vector3d hologramOutDirection(const HologramPointGeometry& g, const Eigen::Vector3d& u_in,
                                     const Eigen::Vector3d& eye_side);

// M (2x2, 1/mm, complex) of the outgoing wave in the basis `out_basis` (two orthonormal
// columns normal to u_out), for an isotropic input beam along u_in with complex radius q_in (mm).
Eigen::Matrix2cd hologramOutputCurvature(const HologramPointGeometry& g, const Eigen::Vector3d& u_in,
                                         std::complex<double> q_in, const Eigen::Vector3d& u_out,
                                         const Eigen::Matrix<double, 3, 2>& out_basis);

}  // namespace fovea
