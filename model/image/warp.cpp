#include "model/image/warp.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include <Eigen/Dense>

namespace fovea::image {

namespace {
int polyOrder(WarpModel m) {
  return m == WarpModel::Poly1 ? 1 : m == WarpModel::Poly2 ? 2 : 3;
}
int termCount(int order) {
  return (order + 1) * (order + 2) / 2;
}

// Monomial row at a normalised point.
Eigen::VectorXd monomials(const Eigen::Vector2d& p, int order) {
  Eigen::VectorXd row(termCount(order));
  int k = 0;
  for (int d = 0; d <= order; ++d)
    for (int j = 0; j <= d; ++j) row[k++] = std::pow(p.x(), d - j) * std::pow(p.y(), j);
  return row;
}

Similarity2d hartley(const std::vector<Eigen::Vector2d>& pts) {
  Similarity2d s;
  for (const auto& p : pts) s.center += p;
  s.center /= static_cast<double>(pts.size());
  double mean = 0;
  for (const auto& p : pts) mean += (p - s.center).norm();
  mean /= static_cast<double>(pts.size());
  s.scale = mean > 0 ? std::sqrt(2.0) / mean : 1.0;
  return s;
}

void checkInput(const std::vector<PointPair>& pairs, WarpModel model) {
  for (std::size_t i = 0; i < pairs.size(); ++i)
    if (!pairs[i].src.allFinite() || !pairs[i].dst.allFinite())
      throw WarpError("pair " + std::to_string(i) + " has a non-finite (NaN or infinite) coordinate");
  const int need = minimumPairs(model);
  if (static_cast<int>(pairs.size()) < need)
    throw WarpError("too few point pairs for " + toString(model) + ": " + std::to_string(pairs.size()) +
                    " given, at least " + std::to_string(need) + " needed");
  // Collinear (or coincident) sources: the spread matrix has a (near) zero eigenvalue.
  std::vector<Eigen::Vector2d> src;
  src.reserve(pairs.size());
  for (const auto& p : pairs) src.push_back(p.src);
  const Similarity2d n = hartley(src);
  Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
  for (const auto& p : src) {
    const Eigen::Vector2d q = n.apply(p);
    spread += q * q.transpose();
  }
  const Eigen::Vector2d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(spread).eigenvalues();
  if (!(ev[0] > 1e-10 * ev[1])) throw WarpError("source points are collinear: a 2-D warp is not determined");
}
}  // namespace

std::string toString(WarpModel m) {
  switch (m) {
    case WarpModel::Poly1:
      return "poly1";
    case WarpModel::Poly2:
      return "poly2";
    case WarpModel::Poly3:
      return "poly3";
    case WarpModel::Homography:
      return "homography";
  }
  return "?";
}

std::optional<WarpModel> warpModelFromString(const std::string& s) {
  for (WarpModel m : {WarpModel::Poly1, WarpModel::Poly2, WarpModel::Poly3, WarpModel::Homography})
    if (toString(m) == s) return m;
  return std::nullopt;
}

int minimumPairs(WarpModel m) {
  return m == WarpModel::Homography ? 4 : termCount(polyOrder(m));
}

std::vector<std::string> polynomialTerms(int order) {
  std::vector<std::string> t;
  auto pw = [](const char* v, int e) {
    return e == 0 ? std::string() : e == 1 ? std::string(v) : v + std::string("^") + std::to_string(e);
  };
  for (int d = 0; d <= order; ++d)
    for (int j = 0; j <= d; ++j) {
      const std::string s = pw("x", d - j) + pw("y", j);
      t.push_back(s.empty() ? "1" : s);
    }
  return t;
}

Eigen::Vector2d Warp2d::apply(const Eigen::Vector2d& src) const {
  if (!mix_.empty()) {
    Eigen::Vector2d out = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < mix_.size(); ++i) out += mix_weights_[i] * mix_[i].apply(src);
    return out;
  }
  if (model_ == WarpModel::Homography) {
    const Eigen::Vector3d h = h_ * src.homogeneous();
    return h.hnormalized();
  }
  return coeffs_ * monomials(norm_.apply(src), polyOrder(model_));
}

nlohmann::json Warp2d::coefficients() const {
  if (!mix_.empty()) {
    nlohmann::json parts = nlohmann::json::array();
    for (std::size_t i = 0; i < mix_.size(); ++i)
      parts.push_back({{"weight", mix_weights_[i]},
                       {"model", toString(mix_[i].model())},
                       {"coefficients", mix_[i].coefficients()}});
    return {{"blend", parts}};
  }
  if (model_ == WarpModel::Homography) {
    nlohmann::json H = nlohmann::json::array();
    for (int r = 0; r < 3; ++r) H.push_back({h_(r, 0), h_(r, 1), h_(r, 2)});
    return {{"H", H}};
  }
  std::vector<double> u(coeffs_.cols()), v(coeffs_.cols());
  for (int k = 0; k < coeffs_.cols(); ++k) {
    u[k] = coeffs_(0, k);
    v[k] = coeffs_(1, k);
  }
  return {{"normalization", {{"center", {norm_.center.x(), norm_.center.y()}}, {"scale", norm_.scale}}},
          {"terms", polynomialTerms(polyOrder(model_))},
          {"u", u},
          {"v", v}};
}

Warp2d Warp2d::identity() {
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(2, 3);
  c(0, 1) = c(1, 2) = 1.0;
  return polynomial(WarpModel::Poly1, Similarity2d{}, c);
}

Warp2d Warp2d::polynomial(WarpModel m, Similarity2d norm, const Eigen::MatrixXd& coeffs) {
  if (m == WarpModel::Homography) throw WarpError("not a polynomial model");
  if (coeffs.rows() != 2 || coeffs.cols() != termCount(polyOrder(m))) throw WarpError("wrong coefficient count");
  Warp2d w;
  w.model_ = m;
  w.norm_ = std::move(norm);
  w.coeffs_ = coeffs;
  return w;
}

Warp2d Warp2d::homography(const Eigen::Matrix3d& H) {
  Warp2d w;
  w.model_ = WarpModel::Homography;
  w.h_ = H / H(2, 2);
  return w;
}

Warp2d Warp2d::blend(const Warp2d& a, const Warp2d& b, double t) {
  if (t <= 0) return a;
  if (t >= 1) return b;
  if (a.mix_.empty() && b.mix_.empty() && a.model_ == b.model_ && a.model_ != WarpModel::Homography &&
      a.norm_.center == b.norm_.center && a.norm_.scale == b.norm_.scale)
    return polynomial(a.model_, a.norm_, (1 - t) * a.coeffs_ + t * b.coeffs_);
  Warp2d w = a;
  w.mix_ = {a, b};
  w.mix_weights_ = {1 - t, t};
  return w;
}

Warp2d fitWarp(const std::vector<PointPair>& pairs, WarpModel model) {
  checkInput(pairs, model);
  std::vector<Eigen::Vector2d> src, dst;
  for (const auto& p : pairs) {
    src.push_back(p.src);
    dst.push_back(p.dst);
  }
  const Similarity2d ns = hartley(src);
  const int n = static_cast<int>(pairs.size());
  if (model != WarpModel::Homography) {
    const int order = polyOrder(model);
    Eigen::MatrixXd A(n, termCount(order));
    Eigen::MatrixXd B(n, 2);
    for (int i = 0; i < n; ++i) {
      A.row(i) = monomials(ns.apply(src[i]), order).transpose();
      B.row(i) = dst[i].transpose();
    }
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const auto& sv = svd.singularValues();
    if (!(sv[sv.size() - 1] > 1e-9 * sv[0]))
      throw WarpError("point pairs are degenerate for " + toString(model) +
                      ": the source points do not constrain every coefficient (e.g. they lie on a conic)");
    Warp2d w;
    w.model_ = model;
    w.norm_ = ns;
    w.coeffs_ = svd.solve(B).transpose();
    return w;
  }
  // Homography: normalised DLT (Hartley & Zisserman, Alg. 4.2), then Gauss-Newton on the
  // geometric (reprojection) error in the normalised frames, with h22 = 1.
  const Similarity2d nd = hartley(dst);
  Eigen::MatrixXd A(2 * Eigen::Index{n}, 9);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d p = ns.apply(src[i]), q = nd.apply(dst[i]);
    const Eigen::Index row = 2 * Eigen::Index{i};
    A.row(row) << -p.x(), -p.y(), -1, 0, 0, 0, q.x() * p.x(), q.x() * p.y(), q.x();
    A.row(row + 1) << 0, 0, 0, -p.x(), -p.y(), -1, q.y() * p.x(), q.y() * p.y(), q.y();
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const auto& sv = svd.singularValues();
  if (n > 4 && !(sv[7] > 1e-9 * sv[0])) throw WarpError("point pairs are degenerate for a homography");
  Eigen::VectorXd h = svd.matrixV().col(8);
  if (std::abs(h[8]) < 1e-12) throw WarpError("homography maps a source point to infinity");
  h /= h[8];
  for (int iter = 0; iter < 20; ++iter) {
    Eigen::MatrixXd J(2 * Eigen::Index{n}, 8);
    Eigen::VectorXd r(2 * Eigen::Index{n});
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d p = ns.apply(src[i]), q = nd.apply(dst[i]);
      const double w = h[6] * p.x() + h[7] * p.y() + 1.0;
      const double u = (h[0] * p.x() + h[1] * p.y() + h[2]) / w;
      const double v = (h[3] * p.x() + h[4] * p.y() + h[5]) / w;
      const Eigen::Index row = 2 * Eigen::Index{i};
      r[row] = u - q.x();
      r[row + 1] = v - q.y();
      J.row(row) << p.x() / w, p.y() / w, 1 / w, 0, 0, 0, -u * p.x() / w, -u * p.y() / w;
      J.row(row + 1) << 0, 0, 0, p.x() / w, p.y() / w, 1 / w, -v * p.x() / w, -v * p.y() / w;
    }
    const Eigen::VectorXd step = J.colPivHouseholderQr().solve(-r);
    for (int k = 0; k < 8; ++k) h[k] += step[k];
    if (step.norm() < 1e-12) break;
  }
  Eigen::Matrix3d Hn;
  Hn << h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], 1.0;
  Eigen::Matrix3d Ts = Eigen::Matrix3d::Identity(), Td = Eigen::Matrix3d::Identity();
  Ts.topLeftCorner<2, 2>() *= ns.scale;
  Ts.topRightCorner<2, 1>() = -ns.scale * ns.center;
  Td.topLeftCorner<2, 2>() *= nd.scale;
  Td.topRightCorner<2, 1>() = -nd.scale * nd.center;
  const Eigen::Matrix3d H = Td.inverse() * Hn * Ts;
  if (!H.allFinite()) throw WarpError("homography fit did not converge");
  return Warp2d::homography(H);
}

double rmsResidual(const Warp2d& w, const std::vector<PointPair>& pairs) {
  if (pairs.empty()) return std::nan("");
  double s = 0;
  for (const auto& p : pairs) s += (w.apply(p.src) - p.dst).squaredNorm();
  return std::sqrt(s / static_cast<double>(pairs.size()));
}

WarpFit fitWarpWithHoldout(const std::vector<PointPair>& pairs, WarpModel model, double fraction, std::uint64_t seed) {
  if (!(fraction >= 0 && fraction < 1)) throw WarpError("hold-out fraction must lie in [0, 1)");
  const int n = static_cast<int>(pairs.size());
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::mt19937_64 rng(seed);
  for (int i = n - 1; i > 0; --i)
    std::swap(order[i], order[static_cast<int>(rng() % static_cast<std::uint64_t>(i + 1))]);
  const int held = static_cast<int>(std::lround(fraction * n));
  std::vector<PointPair> fitSet, holdSet;
  WarpFit r;
  for (int i = 0; i < n; ++i) {
    if (i < held) {
      holdSet.push_back(pairs[order[i]]);
      r.holdout_indices.push_back(order[i]);
    } else {
      fitSet.push_back(pairs[order[i]]);
    }
  }
  std::sort(r.holdout_indices.begin(), r.holdout_indices.end());
  if (held > 0 && static_cast<int>(fitSet.size()) < minimumPairs(model))
    throw WarpError("too few point pairs left after holding out " + std::to_string(held) + " of " + std::to_string(n) +
                    ": " + toString(model) + " needs " + std::to_string(minimumPairs(model)));
  r.warp = fitWarp(fitSet, model);
  r.rms_fit_px = rmsResidual(r.warp, fitSet);
  r.rms_holdout_px = rmsResidual(r.warp, holdSet);
  r.fitted = static_cast<int>(fitSet.size());
  r.held_out = held;
  return r;
}

}  // namespace fovea::image
