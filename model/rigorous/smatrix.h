#pragma once
// Scattering matrices of a layered region and the Redheffer star product (Li, JOSA A 13,
// 1024 (1996)). Port 1 is the −z side (cover), port 2 the +z side (substrate). With a and b the
// amplitudes of the forward (+z) and backward (−z) waves in the reference media on either side:
//   b1 = S11 a1 + S12 b2',  a2' = S21 a1 + S22 b2'   (primed: port 2)
// i.e. S11 reflects from the left, S21 transmits left→right, S12 right→left, S22 reflects from
// the right. Every exponential inside is a decaying or unit-modulus one, so products of
// S-matrices never overflow, whatever the thickness.

#include <Eigen/Dense>

namespace fovea::rigorous {

struct SMatrix {
  Eigen::MatrixXcd s11, s12, s21, s22;

  // The S-matrix of nothing: no reflection, unit transmission.
  static SMatrix identity(Eigen::Index n);
};

// a ⊗ b: region `a` followed (towards +z) by region `b`.
SMatrix starProduct(const SMatrix& a, const SMatrix& b);

// D S D^{-1} on every block, D = diag(d): the S-matrix of a structure shifted along x when the
// reference media are homogeneous (their mode matrices commute with D).
SMatrix conjugated(const SMatrix& s, const Eigen::VectorXcd& d);

}  // namespace fovea::rigorous
