#pragma once
// 2-D warps between display pixels and camera / visual-angle coordinates (seed B.2.1):
// polynomials of order 1-3 (the seed fits 2nd order "instead of homography because the
// diffraction at the HOE gratings is non-linear") and a homography for comparison, fitted
// by least squares, with a held-out residual from a seeded split.
//
// Conditioning: source coordinates are normalised (centroid to the origin, mean distance
// sqrt(2), Hartley 1997) before building the design matrix; the homography normalises the
// destination too. The normalisation is part of the warp, so apply() takes raw coordinates.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace fovea::image {

enum class WarpModel { Poly1, Poly2, Poly3, Homography };
std::string toString(WarpModel m);
std::optional<WarpModel> warpModelFromString(const std::string& s);
// Fewest point pairs that determine the model (3, 6, 10, 4).
int minimumPairs(WarpModel m);

struct PointPair {
  Eigen::Vector2d src, dst;
};

// Degenerate input: too few pairs, collinear points, non-finite coordinates.
class WarpError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct Similarity2d {  // p' = scale * (p - center)
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double scale = 1.0;
  Eigen::Vector2d apply(const Eigen::Vector2d& p) const { return scale * (p - center); }
};

class Warp2d {
 public:
  Warp2d() = default;
  WarpModel model() const { return model_; }
  Eigen::Vector2d apply(const Eigen::Vector2d& src) const;
  // {"normalization":{"center":[x,y],"scale":s}, "terms":["1","x","y",...], "u":[...], "v":[...]}
  // for polynomials (terms in the normalised source coordinates, u/v in destination
  // units); {"H":[[...],[...],[...]]} (raw coordinates, H[2][2] = 1) for a homography.
  nlohmann::json coefficients() const;
  static Warp2d identity();

  // A polynomial warp from its normalisation and coefficients (rows u, v; columns the
  // monomials in the order of polynomialTerms()).
  static Warp2d polynomial(WarpModel m, Similarity2d norm, const Eigen::MatrixXd& coeffs);
  static Warp2d homography(const Eigen::Matrix3d& H);
  // Pointwise blend (1-t) a + t b of two warps, for gaze interpolation. Polynomial warps
  // sharing the normalisation blend their coefficients (exactly pointwise); otherwise the
  // result keeps both and mixes their outputs.
  static Warp2d blend(const Warp2d& a, const Warp2d& b, double t);

 private:
  friend Warp2d fitWarp(const std::vector<PointPair>&, WarpModel);
  WarpModel model_ = WarpModel::Poly1;
  Similarity2d norm_;
  Eigen::MatrixXd coeffs_;  // 2 x terms
  Eigen::Matrix3d h_ = Eigen::Matrix3d::Identity();
  std::vector<Warp2d> mix_;  // non-empty: the warp is the weighted sum of these
  std::vector<double> mix_weights_;
};

// Monomials x^i y^j, i + j <= order, ordered by degree then by falling power of x:
// 1, x, y, x^2, xy, y^2, x^3, x^2y, xy^2, y^3.
std::vector<std::string> polynomialTerms(int order);

// Least-squares fit; throws WarpError on degenerate input.
Warp2d fitWarp(const std::vector<PointPair>& pairs, WarpModel model);

struct WarpFit {
  Warp2d warp;
  double rms_fit_px = 0;      // RMS Euclidean residual over the fitted pairs
  double rms_holdout_px = 0;  // over the held-out pairs (NaN when none are held out)
  int fitted = 0, held_out = 0;
  std::vector<int> holdout_indices;
};
// Holds out round(fraction * n) pairs chosen by a seeded shuffle (a fixed Fisher-Yates on
// a 64-bit Mersenne twister, the same on every platform), fits the rest.
WarpFit fitWarpWithHoldout(const std::vector<PointPair>& pairs, WarpModel model, double holdout_fraction,
                           std::uint64_t seed);

double rmsResidual(const Warp2d& w, const std::vector<PointPair>& pairs);

}  // namespace fovea::image
