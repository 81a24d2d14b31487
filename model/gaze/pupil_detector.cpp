#include "model/gaze/pupil_detector.h"
#include "model/units.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include <opencv2/imgproc.hpp>

namespace fovea::gaze {
namespace {

constexpr int kGlintLevel = 235;  // 8-bit: a corneal reflection saturates the sensor
constexpr int kSupportBins = 72;

struct Proposal {
  cv::Point2d centre;
  double radius_px = 0;
  double contrast_dn = 0;
};

// Best centre-surround response over positions and radii on a 1/scale frame: mean of a
// (2r)^2 box subtracted from the mean of the ring out to (4r)^2 around it, less half the
// centre's mean level.
Proposal propose(const cv::Mat& grey, const PupilDetectorOptions& o) {
  const int scale = std::max(1, std::min(grey.cols, grey.rows) / 100);
  cv::Mat small;
  cv::resize(grey, small, cv::Size(grey.cols / scale, grey.rows / scale), 0, 0, cv::INTER_AREA);
  cv::Mat integral;
  cv::integral(small, integral, CV_32S);
  const auto box = [&](int x0, int y0, int x1, int y1) {
    return static_cast<double>(integral.at<int>(y1, x1) - integral.at<int>(y0, x1) - integral.at<int>(y1, x0) +
                               integral.at<int>(y0, x0));
  };
  Proposal best;
  double best_score = -1e9;
  const double r_min = std::max(1.0, o.min_diameter_px / (2.0 * scale) * 0.8);
  const double r_max = o.max_diameter_px / (2.0 * scale) * 0.8;  // the inner box sits inside the disc
  // Radii grow geometrically by 1.35 from r_min up to r_max (same sequence as rf *= 1.35).
  double rf = r_min;
  while (rf <= r_max) {
    const int r = std::max(1, static_cast<int>(std::lround(rf)));
    rf *= 1.35;
    const double inner_n = 4.0 * r * r, outer_n = 16.0 * r * r - inner_n;
    for (int y = 2 * r; y + 2 * r <= small.rows; y += 1)
      for (int x = 2 * r; x + 2 * r <= small.cols; x += 1) {
        const double inner = box(x - r, y - r, x + r, y + r);
        const double outer = box(x - 2 * r, y - 2 * r, x + 2 * r, y + 2 * r) - inner;
        const double inner_mean = inner / inner_n, response = outer / outer_n - inner_mean;
        // The iris against the sclera contrasts as much as the pupil against the iris: the
        // pupil is the darker centre, so darkness counts too.
        const double score = response - 0.5 * inner_mean;
        if (score > best_score) {
          best_score = score;
          best = {cv::Point2d((x + 0.5) * scale, (y + 0.5) * scale), static_cast<double>(r * scale) / 0.8, response};
        }
      }
  }
  return best;
}

int medianOf(const cv::Mat& roi) {
  std::array<int, 256> hist{};
  for (int y = 0; y < roi.rows; ++y) {
    const auto* p = roi.ptr<std::uint8_t>(y);
    for (int x = 0; x < roi.cols; ++x) ++hist[p[x]];
  }
  const int half = (roi.rows * roi.cols) / 2;
  int acc = 0;
  for (int v = 0; v < 256; ++v)
    if ((acc += hist[v]) > half) return v;
  return 255;
}

struct EllipseFrame {
  cv::Point2d c;
  double a, b, cs, sn;  // semi-axes, orientation of a
};

EllipseFrame frameOf(const cv::RotatedRect& r) {
  const double t = r.angle * kPi / 180;
  return {r.center, r.size.width / 2.0, r.size.height / 2.0, std::cos(t), std::sin(t)};
}

// Approximate distance of a point to the ellipse: along the ray from its centre.
double distanceTo(const EllipseFrame& e, const cv::Point2d& p) {
  const double dx = p.x - e.c.x, dy = p.y - e.c.y;
  const double u = dx * e.cs + dy * e.sn, v = -dx * e.sn + dy * e.cs;
  const double rho = std::hypot(u / e.a, v / e.b);
  return rho > 1e-9 ? std::hypot(dx, dy) * std::abs(1 - 1 / rho) : std::max(e.a, e.b);
}

bool plausible(const cv::RotatedRect& r, const PupilDetectorOptions& o, const cv::Rect& roi) {
  const double major = std::max(r.size.width, r.size.height), minor = std::min(r.size.width, r.size.height);
  return std::isfinite(major) && std::isfinite(minor) && minor >= o.min_diameter_px && major <= o.max_diameter_px &&
         minor >= 0.5 * major && roi.contains(cv::Point(r.center));
}

std::vector<cv::Point2f> inliersOf(const cv::RotatedRect& r, const std::vector<cv::Point2f>& pts, double tol) {
  const EllipseFrame e = frameOf(r);
  std::vector<cv::Point2f> in;
  for (const auto& p : pts)
    if (distanceTo(e, p) < tol) in.push_back(p);
  return in;
}

using Support = std::array<bool, kSupportBins>;
int supportBin(double t) {  // t = atan2 of the normalised ellipse coordinates, in (-pi, pi]
  return std::clamp(static_cast<int>((t + kPi) / (2 * kPi) * kSupportBins), 0, kSupportBins - 1);
}

// The parameter bins of the outline (kSupportBins equal bins) that hold an inlier.
Support outlineSupport(const cv::RotatedRect& r, const std::vector<cv::Point2f>& inliers) {
  const EllipseFrame e = frameOf(r);
  Support hit{};
  for (const auto& p : inliers) {
    const double dx = p.x - e.c.x, dy = p.y - e.c.y;
    const double u = (dx * e.cs + dy * e.sn) / e.a, v = (-dx * e.sn + dy * e.cs) / e.b;
    hit[supportBin(std::atan2(v, u))] = true;
  }
  return hit;
}

// Mean grey level on the ellipse scaled by s, sampled (32 points) only in the directions
// where the outline is seen: where an eyelid covers the pupil, there is skin inside.
double ringMean(const cv::Mat& grey, const cv::RotatedRect& r, double s, const Support& seen) {
  const EllipseFrame e = frameOf(r);
  double sum = 0;
  int n = 0;
  for (int i = 0; i < 32; ++i) {
    const double t = 2 * kPi * i / 32 - kPi;
    if (!seen[supportBin(t)]) continue;
    const double u = s * e.a * std::cos(t), v = s * e.b * std::sin(t);
    const int x = cvRound(e.c.x + u * e.cs - v * e.sn), y = cvRound(e.c.y + u * e.sn + v * e.cs);
    if (x < 0 || y < 0 || x >= grey.cols || y >= grey.rows) continue;
    const int g = grey.at<std::uint8_t>(y, x);
    if (g >= kGlintLevel) continue;
    sum += g;
    ++n;
  }
  return n ? sum / n : 255;
}

PupilDetection notFound(std::string reason, std::vector<cv::Point2d> glints = {}) {
  PupilDetection d;
  d.reason = std::move(reason);
  d.glints_px = std::move(glints);
  return d;
}

}  // namespace

cv::Mat toGrey8(const cv::Mat& image) {
  if (image.empty()) return {};
  cv::Mat grey;
  switch (image.channels()) {
    case 1:
      grey = image;
      break;
    case 3:
      cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
      break;
    case 4:
      cv::cvtColor(image, grey, cv::COLOR_BGRA2GRAY);
      break;
    default:
      return {};
  }
  if (grey.depth() == CV_8U) return grey;
  if (grey.depth() == CV_32F || grey.depth() == CV_64F) {
    cv::Mat out;
    grey.convertTo(out, CV_8U, 255.0);
    return out;
  }
  if (grey.depth() == CV_16U) {
    cv::Mat out;
    grey.convertTo(out, CV_8U, 1.0 / 257.0);
    return out;
  }
  return {};
}

PupilDetection detectPupil(const cv::Mat& image, const PupilDetectorOptions& o) {
  if (image.empty()) return notFound("empty frame");
  const cv::Mat grey = toGrey8(image);
  if (grey.empty()) return notFound("unsupported image type");
  if (grey.cols < 2 * o.min_diameter_px || grey.rows < 2 * o.min_diameter_px) return notFound("frame too small");

  // 1. Proposal.
  const Proposal prop = propose(grey, o);
  if (prop.contrast_dn < o.min_contrast_dn) return notFound("no dark region (eye closed or out of view)");

  // 2. Region of interest, threshold, glints.
  const int half = static_cast<int>(std::ceil(2.4 * prop.radius_px)) + 4;
  const cv::Rect roi = cv::Rect(cvRound(prop.centre.x) - half, cvRound(prop.centre.y) - half, 2 * half, 2 * half) &
                       cv::Rect(0, 0, grey.cols, grey.rows);
  const cv::Mat patch = grey(roi);
  const int inner_half = std::max(2, static_cast<int>(0.5 * prop.radius_px));
  const cv::Rect inner = cv::Rect(cvRound(prop.centre.x) - roi.x - inner_half,
                                  cvRound(prop.centre.y) - roi.y - inner_half, 2 * inner_half, 2 * inner_half) &
                         cv::Rect(0, 0, patch.cols, patch.rows);
  if (inner.area() == 0) return notFound("no dark region (eye closed or out of view)");
  const int pupil_level = medianOf(patch(inner)), surround_level = medianOf(patch);
  if (surround_level - pupil_level < o.min_contrast_dn) return notFound("no pupil contrast (eye closed?)");
  const double threshold = pupil_level + 0.45 * (surround_level - pupil_level);

  cv::Mat glint_mask;
  cv::threshold(patch, glint_mask, kGlintLevel - 1, 255, cv::THRESH_BINARY);
  std::vector<cv::Point2d> glints;
  {
    cv::Mat labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(glint_mask, labels, stats, centroids, 8, CV_32S);
    for (int i = 1; i < n; ++i) {
      const int area = stats.at<int>(i, cv::CC_STAT_AREA);
      if (area >= 1 && area <= 80)
        glints.emplace_back(centroids.at<double>(i, 0) + roi.x, centroids.at<double>(i, 1) + roi.y);
    }
  }
  cv::dilate(glint_mask, glint_mask, cv::getStructuringElement(cv::MORPH_ELLIPSE, {5, 5}));

  cv::Mat dark;
  cv::threshold(patch, dark, threshold, 255, cv::THRESH_BINARY_INV);
  dark |= glint_mask;  // glints on the pupil leave no holes
  cv::morphologyEx(dark, dark, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_ELLIPSE, {5, 5}));
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(dark, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  const cv::Point2d pc(prop.centre.x - roi.x, prop.centre.y - roi.y);
  int pick = -1;
  double pick_score = 0;
  for (int i = 0; i < static_cast<int>(contours.size()); ++i) {
    const double area = cv::contourArea(contours[i]);
    if (area < kPi * o.min_diameter_px * o.min_diameter_px / 16) continue;
    const double d = cv::pointPolygonTest(contours[i], cv::Point2f(pc), true);
    const double score = area / (1 + std::max(0.0, -d));  // large, and containing the proposal
    if (score > pick_score) pick = i, pick_score = score;
  }
  if (pick < 0) return notFound("no dark blob of pupil size", glints);

  // 3. Edge points: the blob's outline minus glint neighbourhoods and region borders, then
  // minus the eyelid edge. Beyond a pupil edge lies the iris; beyond an eyelid cutting the
  // pupil, brighter skin. The eyelid's chord is shorter than the arc left when at most half
  // the pupil is covered, so the median level beyond the outline is the iris's.
  const cv::Moments m = cv::moments(contours[pick]);
  const cv::Point2d centroid(m.m10 / m.m00, m.m01 / m.m00);
  struct EdgePoint {
    cv::Point p;
    int beyond;
  };
  std::vector<EdgePoint> outline;
  std::array<int, 256> beyond_hist{};
  for (const auto& p : contours[pick]) {
    if (p.x <= 1 || p.y <= 1 || p.x >= patch.cols - 2 || p.y >= patch.rows - 2) continue;
    if (glint_mask.at<std::uint8_t>(p.y, p.x)) continue;
    const cv::Point2d dir = cv::Point2d(p) - centroid;
    const double len = std::max(1e-9, std::hypot(dir.x, dir.y));
    const int ox = std::clamp(cvRound(p.x + 4 * dir.x / len), 0, patch.cols - 1);
    const int oy = std::clamp(cvRound(p.y + 4 * dir.y / len), 0, patch.rows - 1);
    const int g = patch.at<std::uint8_t>(oy, ox);
    outline.push_back({p, g});
    ++beyond_hist[g];
  }
  int iris_level = 255;
  for (int v = 0, acc = 0; v < 256; ++v)
    if ((acc += beyond_hist[v]) * 2 > static_cast<int>(outline.size())) {
      iris_level = v;
      break;
    }
  const double lid_level = iris_level + std::max(18.0, 0.3 * (iris_level - pupil_level));
  std::vector<cv::Point2f> pts;
  for (const auto& e : outline)
    if (e.beyond <= lid_level || e.beyond >= kGlintLevel)
      pts.emplace_back(static_cast<float>(e.p.x + roi.x), static_cast<float>(e.p.y + roi.y));
  if (pts.size() < 12) return notFound("too few pupil edge points", glints);

  // 4. RANSAC ellipse fit.
  const double tol = 1.5;
  std::mt19937 rng(o.seed);
  std::uniform_int_distribution<std::size_t> pickPoint(0, pts.size() - 1);
  cv::RotatedRect best;
  std::size_t best_inliers = 0;
  const cv::Rect frame(0, 0, grey.cols, grey.rows);
  for (int it = 0; it < o.ransac_iterations; ++it) {
    std::vector<cv::Point2f> sample;
    sample.reserve(5);
    for (int k = 0; k < 5; ++k) sample.push_back(pts[pickPoint(rng)]);
    cv::RotatedRect r;
    try {
      r = cv::fitEllipse(sample);
    } catch (const cv::Exception&) {
      continue;
    }
    if (!plausible(r, o, frame)) continue;
    const std::size_t n = inliersOf(r, pts, tol).size();
    if (n > best_inliers) best = r, best_inliers = n;
  }
  if (best_inliers < 8) return notFound("no ellipse fits the pupil outline", glints);
  for (int refit = 0; refit < 2; ++refit) {
    const std::vector<cv::Point2f> in = inliersOf(best, pts, tol);
    if (in.size() < 6) break;
    cv::RotatedRect r;
    try {
      r = cv::fitEllipse(in);
    } catch (const cv::Exception&) {
      break;
    }
    if (!plausible(r, o, frame)) break;
    best = r;
  }
  const std::vector<cv::Point2f> inliers = inliersOf(best, pts, tol);

  // 5. Confidence: outline support times contrast (inside dark, outside the surround),
  // both over the part of the outline that is seen.
  const Support seen = outlineSupport(best, inliers);
  const double support = static_cast<double>(std::count(seen.begin(), seen.end(), true)) / kSupportBins;
  const double inside = ringMean(grey, best, 0.5, seen), outside = ringMean(grey, best, 1.35, seen);
  if (inside > threshold) return notFound("fitted ellipse is not dark inside", glints);
  const double contrast = std::clamp((outside - inside) / 60.0, 0.0, 1.0);
  const double confidence = std::clamp(support * contrast, 0.0, 1.0);
  if (confidence < o.min_confidence) return notFound("low confidence", glints);

  PupilDetection d;
  d.found = true;
  d.confidence = confidence;
  d.ellipse.centre = best.center;
  d.ellipse.major_px = std::max(best.size.width, best.size.height);
  d.ellipse.minor_px = std::min(best.size.width, best.size.height);
  d.ellipse.angle_deg = best.size.width >= best.size.height ? best.angle : best.angle + 90;
  d.glints_px = std::move(glints);
  return d;
}

}  // namespace fovea::gaze
