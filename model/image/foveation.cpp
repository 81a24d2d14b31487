#include "model/image/foveation.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "model/analysis/foveal_optics.h"
#include "model/color/srgb.h"
#include "model/image/flip.h"
#include "model/image/image_io.h"

namespace fovea::image {

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
constexpr int kBlurLevels = 5;

// Equal-angle image: pixel centre <-> visual angle, for an image of `size` spanning `fov`
// centred on `centre` (yaw right, pitch up; rows run downwards).
struct AngleGrid {
  cv::Size size;
  std::array<double, 2> fov, centre;
  double px(double yaw) const { return ((yaw - centre[0]) / fov[0] + 0.5) * size.width - 0.5; }
  double py(double pitch) const { return ((centre[1] - pitch) / fov[1] + 0.5) * size.height - 0.5; }
  double yaw(double x) const { return centre[0] + ((x + 0.5) / size.width - 0.5) * fov[0]; }
  double pitch(double y) const { return centre[1] - ((y + 0.5) / size.height - 0.5) * fov[1]; }
};

// Columns [first, last] of a row whose pixel centres lie within `radius` of `centre_yaw`,
// for a row at pitch offset `dp` (empty when first > last).
inline std::pair<int, int> discColumns(double radius, double dp, double centre_yaw, double x_of_yaw0, double px_per_deg,
                                       int width) {
  const double h2 = radius * radius - dp * dp;
  if (h2 < 0) return {1, 0};
  const double h = std::sqrt(h2);
  const int first = std::max(0, static_cast<int>(std::ceil(x_of_yaw0 + (centre_yaw - h) * px_per_deg)));
  const int last = std::min(width - 1, static_cast<int>(std::floor(x_of_yaw0 + (centre_yaw + h) * px_per_deg)));
  return {first, last};
}
}  // namespace

DisplayAngles displayAngles(const Scene& s) {
  DisplayAngles a;
  a.peripheral_fov_deg = s.projector.fov_deg;
  a.peripheral_px = s.projector.pixels;
  a.foveal_fov_deg = fovealFovDeg(s);
  a.foveal_px = s.foveal_display.pixels;
  return a;
}

double matchingBlurSigmaDeg(double foveal_cpd, double peripheral_cpd) {
  const double pf = 1.0 / (2.0 * foveal_cpd), pp = 1.0 / (2.0 * peripheral_cpd);
  return pp > pf ? std::sqrt((pp * pp - pf * pf) / 12.0) : 0.0;
}

BlendProfile blendProfile(const Scene& s, bool enabled) {
  BlendProfile p;
  p.blur_start_deg = s.foveation.blur_start_deg;
  p.blend_start_deg = s.foveation.blend_start_deg;
  p.blend_end_deg = s.foveation.blend_end_deg;
  const DisplayAngles a = displayAngles(s);
  p.sigma_match_deg = matchingBlurSigmaDeg(a.fovealCpd(), a.peripheralCpd());
  p.enabled = enabled;
  return p;
}

double BlendProfile::fovealWeight(double e) const {
  if (!enabled) return e < blend_start_deg ? 1.0 : 0.0;
  if (e <= blend_start_deg) return 1.0;
  if (e >= blend_end_deg) return 0.0;
  return (blend_end_deg - e) / (blend_end_deg - blend_start_deg);
}

double BlendProfile::blurSigmaDeg(double e) const {
  if (!enabled || e <= blur_start_deg) return 0.0;
  if (e >= blend_start_deg) return sigma_match_deg;
  return sigma_match_deg * (e - blur_start_deg) / (blend_start_deg - blur_start_deg);
}

FoveatedCompositor::FoveatedCompositor(const Scene& scene, bool blend, GazeWarpTables warps)
    : angles_(displayAngles(scene)), profile_(blendProfile(scene, blend)), warps_(std::move(warps)) {}

void FoveatedCompositor::setTarget(const cv::Mat& target) {
  CV_Assert(target.type() == CV_32FC3 && !target.empty());
  target_ = target;
  const double sigmaPx = profile_.sigma_match_deg * targetPpd();
  blur_levels_.assign(1, target_);
  if (profile_.enabled && sigmaPx > 1e-3)
    for (int k = 1; k < kBlurLevels; ++k) {
      cv::Mat b;
      cv::GaussianBlur(target_, b, cv::Size(0, 0), sigmaPx * k / (kBlurLevels - 1), 0, cv::BORDER_REPLICATE);
      blur_levels_.push_back(b);
    }
  // The projector shows the target at its own resolution (area average = its pixels).
  cv::resize(target_, peripheral_base_, cv::Size(angles_.peripheral_px[0], angles_.peripheral_px[1]), 0, 0,
             cv::INTER_AREA);
  cv::resize(peripheral_base_, perceived_base_, target_.size(), 0, 0, cv::INTER_LINEAR);
  peripheral_ideal_ = peripheral_base_.clone();
  perceived_ = perceived_base_.clone();
  foveal_ideal_ = cv::Mat::zeros(angles_.foveal_px[1], angles_.foveal_px[0], CV_32FC3);
  foveal_dirty_ = peripheral_dirty_ = perceived_dirty_ = cv::Rect();
}

cv::Rect FoveatedCompositor::discRect(cv::Size size, std::array<double, 2> fov, std::array<double, 2> centre,
                                      double radius) const {
  const AngleGrid g{size, fov, {0.0, 0.0}};
  const int x0 = static_cast<int>(std::floor(g.px(centre[0] - radius))) - 2;
  const int x1 = static_cast<int>(std::ceil(g.px(centre[0] + radius))) + 2;
  const int y0 = static_cast<int>(std::floor(g.py(centre[1] + radius))) - 2;
  const int y1 = static_cast<int>(std::ceil(g.py(centre[1] - radius))) + 2;
  return cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1) & cv::Rect(0, 0, size.width, size.height);
}

void FoveatedCompositor::renderFoveal() {
  // Two steps. (1) On the target's own grid, inside the disc of the foveal extent, the
  // blended foveal content: the target blurred to sigma(eps) (interpolated between cached
  // blur levels) times the foveal weight w(eps); direct pixel reads, no resampling.
  // (2) The foveal display's pixels sample that content bilinearly (cv::warpAffine: the
  // map from foveal pixels to target pixels is affine in the equal-angle model). Where no
  // blur or weight applies, this equals sampling the target itself bilinearly.
  const cv::Size size = foveal_ideal_.size();
  const AngleGrid grid{size, angles_.foveal_fov_deg, gaze_};
  const AngleGrid tgt{target_.size(), angles_.peripheral_fov_deg, {0.0, 0.0}};
  const double extent = profile_.fovealExtentDeg();
  const int levels = static_cast<int>(blur_levels_.size());
  const BlendProfile p = profile_;
  const double sigmaToLevel = p.sigma_match_deg > 0 ? (levels - 1) / p.sigma_match_deg : 0.0;

  const cv::Rect rectT = discRect(target_.size(), angles_.peripheral_fov_deg, gaze_, extent);
  // A view into a buffer of the largest (unclipped) disc box: no reallocation (and no
  // page faults) when the disc is clipped differently at the target's edges.
  const int side = 2 * static_cast<int>(std::ceil(extent * targetPpd())) + 8;
  if (foveal_content_buf_.rows < side || foveal_content_buf_.cols < side)
    foveal_content_buf_.create(std::max(side, rectT.height), std::max(side, rectT.width), CV_32FC3);
  foveal_content_ = foveal_content_buf_(cv::Rect(0, 0, rectT.width, rectT.height));
  foveal_content_.setTo(cv::Scalar::all(0));
  const double ppdT = target_.cols / angles_.peripheral_fov_deg[0];
  const double x0T = tgt.px(0.0);
  // Radius within which the foveal weight is 1 and there is no blur (just inside it, so
  // that rounding never copies a pixel the ramps would change).
  const double inner = (p.enabled ? std::min(p.blur_start_deg, p.blend_start_deg) : p.blend_start_deg) * (1.0 - 1e-9);
  cv::parallel_for_(cv::Range(rectT.y, rectT.y + rectT.height), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      auto* out = foveal_content_.ptr<cv::Vec3f>(y - rectT.y) - rectT.x;
      const double dp = tgt.pitch(y) - gaze_[1];
      const auto [first, last] = discColumns(extent, dp, gaze_[0], x0T, ppdT, target_.cols);
      // Inside the inner disc (weight 1, no blur) the content is the target itself: copy.
      const auto [innerFirst, innerLast] = discColumns(inner, dp, gaze_[0], x0T, ppdT, target_.cols);
      const bool hasInner = innerFirst <= innerLast;
      if (hasInner)
        std::copy(blur_levels_[0].ptr<cv::Vec3f>(y) + innerFirst, blur_levels_[0].ptr<cv::Vec3f>(y) + innerLast + 1,
                  out + innerFirst);
      for (int x = first; x <= last; ++x) {
        if (hasInner && x == innerFirst) {
          x = innerLast;
          continue;
        }
        const double dyaw = tgt.yaw(x) - gaze_[0];
        const double ecc = std::sqrt(dyaw * dyaw + dp * dp);
        const double w = p.fovealWeight(ecc);
        if (w <= 0.0) continue;
        cv::Vec3f v;
        if (levels == 1 || ecc <= p.blur_start_deg) {
          v = blur_levels_[0].ptr<cv::Vec3f>(y)[x];
        } else {
          const double s = p.blurSigmaDeg(ecc) * sigmaToLevel;
          const int i0 = std::min(static_cast<int>(s), levels - 2);
          const float f = static_cast<float>(s - i0);
          v = blur_levels_[i0].ptr<cv::Vec3f>(y)[x];
          if (f > 0) v += f * (blur_levels_[i0 + 1].ptr<cv::Vec3f>(y)[x] - v);
        }
        out[x] = static_cast<float>(w) * v;
      }
    }
  });

  // The display follows the gaze, so the disc sits at the same display pixels for every
  // gaze: warpAffine below rewrites all of rectF, nothing outside it ever lights up.
  const cv::Rect rectF = discRect(size, angles_.foveal_fov_deg, {0.0, 0.0}, extent);
  if (!foveal_dirty_.empty() && foveal_dirty_ != rectF) foveal_ideal_(foveal_dirty_).setTo(cv::Scalar::all(0));
  if (!rectF.empty() && !rectT.empty()) {
    // Foveal pixel xf (in rectF) -> target pixel tgt.px(grid.yaw(xf)) -> content column.
    const double ax = tgt.px(grid.yaw(1)) - tgt.px(grid.yaw(0)), bx = tgt.px(grid.yaw(rectF.x)) - rectT.x;
    const double ay = tgt.py(grid.pitch(1)) - tgt.py(grid.pitch(0)), by = tgt.py(grid.pitch(rectF.y)) - rectT.y;
    const cv::Matx23d m(ax, 0, bx, 0, ay, by);
    cv::Mat dst = foveal_ideal_(rectF);
    cv::warpAffine(foveal_content_, dst, m, rectF.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT,
                   cv::Scalar::all(0));
  }
  foveal_dirty_ = rectF;
}

void FoveatedCompositor::renderPeripheral() {
  const cv::Size size = peripheral_ideal_.size();
  const AngleGrid grid{size, angles_.peripheral_fov_deg, {0.0, 0.0}};
  if (!peripheral_dirty_.empty()) peripheral_base_(peripheral_dirty_).copyTo(peripheral_ideal_(peripheral_dirty_));
  const cv::Rect rect = discRect(size, angles_.peripheral_fov_deg, gaze_, profile_.fovealExtentDeg());
  cv::parallel_for_(cv::Range(rect.y, rect.y + rect.height), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      auto* out = peripheral_ideal_.ptr<cv::Vec3f>(y);
      const auto* base = peripheral_base_.ptr<cv::Vec3f>(y);
      const double dp = grid.pitch(y) - gaze_[1];
      for (int x = rect.x; x < rect.x + rect.width; ++x) {
        const double dx = grid.yaw(x) - gaze_[0];
        out[x] = static_cast<float>(1.0 - profile_.fovealWeight(std::sqrt(dx * dx + dp * dp))) * base[x];
      }
    }
  });
  peripheral_dirty_ = rect;
}

void FoveatedCompositor::renderPerceived() {
  // Each display mapped back to visual angle (the target grid) by bilinear interpolation
  // of its own pixels, i.e. at the angular resolution it delivers, then added. Both maps
  // from target pixels to display pixels are affine in the equal-angle model, so
  // cv::warpAffine does the interpolation (vectorised; sub-pixel positions quantised to
  // 1/32 px). The projector's edge pixels extend outwards (as cv::resize does for the
  // cached base); the foveal display is dark beyond its edge.
  const AngleGrid grid{target_.size(), angles_.peripheral_fov_deg, {0.0, 0.0}};
  const AngleGrid per{peripheral_ideal_.size(), angles_.peripheral_fov_deg, {0.0, 0.0}};
  const AngleGrid fov{foveal_ideal_.size(), angles_.foveal_fov_deg, gaze_};
  if (!perceived_dirty_.empty()) perceived_base_(perceived_dirty_).copyTo(perceived_(perceived_dirty_));
  // Reach of the changed projector pixels through the bilinear upsampling: one of them.
  const double margin = 1.0 / angles_.peripheralPpd();
  const cv::Rect rect =
      discRect(target_.size(), angles_.peripheral_fov_deg, gaze_, profile_.fovealExtentDeg() + margin);
  perceived_dirty_ = rect;
  if (rect.empty()) return;
  auto affine = [&](const AngleGrid& to) {
    // Target pixel (rect.x + i, rect.y + j) -> display pixel (a i + b, c j + d).
    const double a = to.px(grid.yaw(rect.x + 1)) - to.px(grid.yaw(rect.x)), b = to.px(grid.yaw(rect.x));
    const double c = to.py(grid.pitch(rect.y + 1)) - to.py(grid.pitch(rect.y)), d = to.py(grid.pitch(rect.y));
    return cv::Matx23d(a, 0, b, 0, c, d);
  };
  if (scratch_.rows < rect.height || scratch_.cols < 2 * rect.width)
    scratch_.create(std::max(scratch_.rows, rect.height), std::max(scratch_.cols, 2 * rect.width), CV_32FC3);
  cv::Mat fromPer = scratch_(cv::Rect(0, 0, rect.width, rect.height));
  cv::Mat fromFov = scratch_(cv::Rect(rect.width, 0, rect.width, rect.height));
  cv::warpAffine(peripheral_ideal_, fromPer, affine(per), rect.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                 cv::BORDER_REPLICATE);
  cv::warpAffine(foveal_ideal_, fromFov, affine(fov), rect.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                 cv::BORDER_CONSTANT, cv::Scalar::all(0));
  cv::Mat dst = perceived_(rect);
  cv::add(fromPer, fromFov, dst);
}

void FoveatedCompositor::update(std::array<double, 2> gaze) {
  CV_Assert(!target_.empty());
  gaze_ = gaze;
  const auto t0 = Clock::now();
  renderFoveal();
  const auto t1 = Clock::now();
  renderPeripheral();
  const auto t2 = Clock::now();
  renderPerceived();
  const auto t3 = Clock::now();
  // Geometric pre-warp of what each display shows (B.2.1: base images through G_f, G_p).
  if (warps_.G_f.empty())
    foveal_out_ = foveal_ideal_;
  else
    foveal_out_ = generateBaseImage(foveal_ideal_, warps_.G_f.at(gaze_), foveal_ideal_.size());
  if (warps_.G_p.empty())
    peripheral_out_ = peripheral_ideal_;
  else
    peripheral_out_ = generateBaseImage(peripheral_ideal_, warps_.G_p.at(gaze_), peripheral_ideal_.size());
  timings_.foveal_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  timings_.peripheral_ms = std::chrono::duration<double, std::milli>(t2 - t1).count();
  timings_.perceived_ms = std::chrono::duration<double, std::milli>(t3 - t2).count();
  timings_.prewarp_ms = msSince(t3);
  timings_.total_ms = msSince(t0);
}

FoveatedCompositor::Seam FoveatedCompositor::seamMetric() const {
  const AngleGrid grid{target_.size(), angles_.peripheral_fov_deg, {0.0, 0.0}};
  const double ppd = targetPpd();
  // Context for FLIP's filters around the annulus.
  const cv::Rect rect = discRect(target_.size(), angles_.peripheral_fov_deg, gaze_, profile_.blend_end_deg + 0.3);
  Seam s;
  if (rect.empty()) return s;
  cv::Mat ref = target_(rect).clone(), test = perceived_(rect).clone();
  for (cv::Mat* m : {&ref, &test})
    m->forEach<cv::Vec3f>([](cv::Vec3f& p, const int*) {
      for (int c = 0; c < 3; ++c) p[c] = color::linearToSrgb(p[c]);
    });
  const cv::Mat err = flipErrorMap(ref, test, ppd);
  std::vector<float> values;
  for (int y = 0; y < rect.height; ++y)
    for (int x = 0; x < rect.width; ++x) {
      const double ecc = std::hypot(grid.yaw(x + rect.x) - gaze_[0], grid.pitch(y + rect.y) - gaze_[1]);
      if (ecc >= profile_.blur_start_deg && ecc <= profile_.blend_end_deg) values.push_back(err.at<float>(y, x));
    }
  if (values.empty()) return s;
  double sum = 0;
  for (float v : values) sum += v;
  s.pixels = static_cast<int>(values.size());
  s.mean_flip = sum / s.pixels;
  std::sort(values.begin(), values.end());
  s.max_flip = values.back();
  s.p95_flip = values[static_cast<std::size_t>(0.95 * (values.size() - 1))];
  return s;
}

}  // namespace fovea::image
