#include "model/rigorous/smatrix.h"

namespace fovea::rigorous {

using Eigen::Index;
using Eigen::MatrixXcd;

SMatrix SMatrix::identity(Index n) {
  SMatrix s;
  s.s11 = MatrixXcd::Zero(n, n);
  s.s22 = MatrixXcd::Zero(n, n);
  s.s12 = MatrixXcd::Identity(n, n);
  s.s21 = MatrixXcd::Identity(n, n);
  return s;
}

// Redheffer star product (Li 1996, eq. 13; Rumpf PIER B 35 (2011), eq. 39): multiple reflections
// between the two regions summed by (I − B11 A22)^{-1}.
SMatrix starProduct(const SMatrix& a, const SMatrix& b) {
  const Index n = a.s11.rows();
  const MatrixXcd id = MatrixXcd::Identity(n, n);
  const Eigen::PartialPivLU<MatrixXcd> lu1(id - b.s11 * a.s22);  // left-going loop
  const Eigen::PartialPivLU<MatrixXcd> lu2(id - a.s22 * b.s11);  // right-going loop
  SMatrix s;
  const MatrixXcd f = lu1.solve(b.s11 * a.s21);  // (I − B11 A22)^{-1} B11 A21
  s.s11 = a.s11 + a.s12 * f;
  s.s12 = a.s12 * lu1.solve(b.s12);
  s.s21 = b.s21 * lu2.solve(a.s21);
  s.s22 = b.s22 + b.s21 * lu2.solve(a.s22 * b.s12);
  return s;
}

SMatrix conjugated(const SMatrix& s, const Eigen::VectorXcd& d) {
  const Eigen::VectorXcd dinv = d.cwiseInverse();
  auto c = [&](const MatrixXcd& m) -> MatrixXcd { return d.asDiagonal() * m * dinv.asDiagonal(); };
  return SMatrix{c(s.s11), c(s.s12), c(s.s21), c(s.s22)};
}

}  // namespace fovea::rigorous
