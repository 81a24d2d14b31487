#include "model/gaze/eye_image_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <opencv2/imgproc.hpp>

#include "model/gaze/thread_scratch.h"
#include "model/scene/scene_geometry.h"
#include "model/units.h"

namespace fovea::gaze {
namespace {

constexpr int kOutlinePoints = 64;

struct CameraFrame {
  Eigen::Vector3d position, forward, right, down;
};

CameraFrame cameraFrame(const IrCameraPose& c) {
  CameraFrame f;
  f.position = c.distance_mm * gazeDirection(c.pose_deg[0], c.pose_deg[1]);
  f.forward = -f.position.normalized();
  f.right = f.forward.cross(Eigen::Vector3d::UnitY()).normalized();
  f.down = f.forward.cross(f.right);
  return f;
}

cv::Point2d project(const IrCameraPose& c, const CameraFrame& f, const Eigen::Vector3d& p) {
  const Eigen::Vector3d v = p - f.position;
  const double z = v.dot(f.forward);
  if (!(z > 1e-6)) return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  return {c.size.width / 2.0 + c.principal_offset_px[0] + c.focal_px * v.dot(f.right) / z,
          c.size.height / 2.0 + c.principal_offset_px[1] + c.focal_px * v.dot(f.down) / z};
}

// A circle of radius r in the plane normal to `axis` through `centre`, as image points.
std::vector<cv::Point2d> projectedCircle(const IrCameraPose& c, const CameraFrame& f, const Eigen::Vector3d& centre,
                                         const Eigen::Vector3d& axis, double r) {
  const Eigen::Vector3d u = axis.cross(Eigen::Vector3d::UnitY()).normalized();
  const Eigen::Vector3d w = axis.cross(u);
  std::vector<cv::Point2d> pts;
  pts.reserve(kOutlinePoints);
  for (int i = 0; i < kOutlinePoints; ++i) {
    const double t = 2 * kPi * i / kOutlinePoints;
    pts.push_back(project(c, f, centre + r * (std::cos(t) * u + std::sin(t) * w)));
  }
  return pts;
}

// Fixed-point polygon for cv::fillPoly (4 fractional bits: sub-pixel edges).
constexpr int kShift = 4;
std::vector<cv::Point> fixedPoint(const std::vector<cv::Point2d>& pts) {
  std::vector<cv::Point> out;
  out.reserve(pts.size());
  for (const auto& p : pts) out.emplace_back(cvRound(p.x * (1 << kShift)), cvRound(p.y * (1 << kShift)));
  return out;
}

void fillPolygon(cv::Mat& img, const std::vector<cv::Point2d>& pts, double value) {
  const std::vector<std::vector<cv::Point>> polys{fixedPoint(pts)};
  cv::fillPoly(img, polys, cv::Scalar(value), cv::LINE_AA, kShift);
}

// The palpebral fissure (eyelid opening) as an image polygon: lid edges are parabolas in
// the plane z = lid_plane_z in front of the rotation centre; the upper lid drops to the
// lower one as the eye closes.
std::vector<cv::Point2d> lidOpening(const IrCameraPose& c, const CameraFrame& f, const EyeAppearance& e,
                                    double lid_plane_z, double upper_shift_mm) {
  const int n = 24;
  std::vector<cv::Point2d> pts;
  const double w = e.lid_half_width_mm, h = e.lid_half_height_mm;
  for (int i = 0; i <= n; ++i) {  // upper lid, left to right
    const double x = -w + 2 * w * i / n, s = 1 - (x / w) * (x / w);
    const double lower = -0.8 * h * s, upper = 1.1 * h * s + upper_shift_mm * s;
    pts.push_back(project(c, f, {x, lower + std::clamp(e.openness, 0.0, 1.0) * (upper - lower), lid_plane_z}));
  }
  for (int i = n - 1; i > 0; --i) {  // lower lid, right to left
    const double x = -w + 2 * w * i / n, s = 1 - (x / w) * (x / w);
    pts.push_back(project(c, f, {x, -0.8 * h * s, lid_plane_z}));
  }
  return pts;
}

// Corneal reflection of a point source seen by the camera: the point of the corneal sphere
// whose normal bisects the directions to the LED and to the camera (exact for distant
// sources; within a few hundredths of a mm at 30 mm for a 7.8 mm cornea).
Eigen::Vector3d glintPoint(const Eigen::Vector3d& cornea_centre, double radius, const Eigen::Vector3d& led,
                           const Eigen::Vector3d& camera) {
  const Eigen::Vector3d n = ((led - cornea_centre).normalized() + (camera - cornea_centre).normalized()).normalized();
  return cornea_centre + radius * n;
}

// The paraxial image through the cornea (one refracting sphere of radius r, index n inside,
// air outside) of a point p of the pupil plane: n/s + 1/s' = (n - 1)/r for the axial point
// at s = anterior chamber depth behind the vertex, lateral magnification m = n s' / -s
// (Atchison & Smith, "Optics of the Human Eye" 2000, ch. 3 and 5). The Le Grand pupil
// (s = 3.6 mm, r = 7.8 mm, n = 1.3375) gives the textbook entrance pupil: 3.05 mm behind the
// apex, magnified 1.13x. Paraxial: views far off the axis see a less foreshortened pupil
// than this (Mathur, Gehrmann, Atchison 2013); the ground truth uses the same map, so truth
// and image agree.
Eigen::Vector3d throughCornea(const Eigen::Vector3d& p, const Eigen::Vector3d& axis, const EyeAppearance& e) {
  const double s = e.anterior_chamber_mm, r = e.cornea_radius_mm, n = e.aqueous_index;
  const double inv_image = (n - 1) / r - n / s;  // 1/s' (negative: a virtual image behind the vertex)
  if (!(s > 0) || std::abs(inv_image) < 1e-12) return p;
  const double s_image = 1 / inv_image, m = n * s_image / -s;
  const Eigen::Vector3d plane_centre = e.pupil_distance_mm * axis;
  const Eigen::Vector3d lateral = (p - plane_centre) - (p - plane_centre).dot(axis) * axis;
  return (e.pupil_distance_mm + e.anterior_chamber_mm + s_image) * axis + m * lateral;
}

struct Layers {
  std::vector<cv::Point2d> pupil, iris, opening;
  cv::Point2d pupil_centre;
  std::vector<cv::Point2d> glints;
};

Layers eyeLayers(const IrCameraPose& c, const CameraFrame& f, const EyeAppearance& e, const EyeFrameSpec& spec,
                 const std::array<double, 2>& gaze) {
  Layers l;
  const Eigen::Vector3d g = gazeDirection(gaze[0], gaze[1]);
  const Eigen::Vector3d pupil_centre = e.pupil_distance_mm * g;
  const Eigen::Vector3d cornea_centre = (e.pupil_distance_mm + e.anterior_chamber_mm - e.cornea_radius_mm) * g;
  if (e.corneal_refraction) {
    const auto refracted = [&](double r) {
      const Eigen::Vector3d u = g.cross(Eigen::Vector3d::UnitY()).normalized(), w = g.cross(u);
      std::vector<cv::Point2d> pts;
      for (int i = 0; i < kOutlinePoints; ++i) {
        const double t = 2 * kPi * i / kOutlinePoints;
        const Eigen::Vector3d p = pupil_centre + r * (std::cos(t) * u + std::sin(t) * w);
        pts.push_back(project(c, f, throughCornea(p, g, e)));
      }
      return pts;
    };
    l.pupil = refracted(e.pupil_diameter_mm / 2);
    l.iris = refracted(e.iris_radius_mm);
    l.pupil_centre = project(c, f, throughCornea(pupil_centre, g, e));
  } else {
    l.pupil = projectedCircle(c, f, pupil_centre, g, e.pupil_diameter_mm / 2);
    l.iris = projectedCircle(c, f, pupil_centre, g, e.iris_radius_mm);
    l.pupil_centre = project(c, f, pupil_centre);
  }
  // The upper lid follows the gaze's pitch a little (lid-eye coordination).
  const double upper_shift = 0.4 * e.pupil_distance_mm * std::sin(gaze[1] * kPi / 180);
  l.opening = lidOpening(c, f, e, e.pupil_distance_mm + 1.5, upper_shift);
  const double cap = std::asin(std::min(1.0, e.iris_radius_mm / e.cornea_radius_mm));
  for (const auto& led : spec.leds_mm) {
    const Eigen::Vector3d p = glintPoint(cornea_centre, e.cornea_radius_mm, led, f.position);
    const Eigen::Vector3d n = (p - cornea_centre).normalized();
    if (std::acos(std::clamp(n.dot(g), -1.0, 1.0)) > cap) continue;  // off the cornea
    l.glints.push_back(project(c, f, p));
  }
  return l;
}

bool inside(const std::vector<cv::Point2d>& poly, const cv::Point2d& p) {
  std::vector<cv::Point2f> f(poly.begin(), poly.end());
  return cv::pointPolygonTest(f, cv::Point2f(p), false) >= 0;
}

struct Texture {
  std::array<double, 6> phase{}, freq{}, amp{};
  cv::Mat skin;  // low-frequency skin variation, 1 +- ~0.1
  struct Lash {
    double x_mm, length_px, bend, angle;
  };
  std::vector<Lash> lashes;
};

// The full-frame images one frame needs, kept per thread across frames (thread_scratch.h: 94 %
// of a binocular run's page faults and a third of its CPU time in the ASan tree were fresh
// images here). Each is fully overwritten before it is read.
struct Scratch {
  cv::Mat skin, skin_scaled, acc, eye, opening, iris_mask, noise, pupil_mask, open_mask, visible_mask;
};

Texture makeTexture(const IrCameraPose& c, const EyeAppearance& e, std::uint32_t seed, cv::Mat& skin) {
  Texture t;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0, 1);
  for (int k = 0; k < 6; ++k) {
    t.phase[k] = 2 * kPi * u01(rng);
    t.freq[k] = 7 + std::floor(40 * u01(rng));  // crypts and radial furrows; 7 ... 46 (< 64: drawIris)
    t.amp[k] = 0.05 + 0.08 * u01(rng);
  }
  cv::Mat low(12, 12, CV_32F);
  for (int y = 0; y < low.rows; ++y)
    for (int x = 0; x < low.cols; ++x) low.at<float>(y, x) = static_cast<float>(1 + 0.2 * (u01(rng) - 0.5));
  cv::resize(low, skin, c.size, 0, 0, cv::INTER_CUBIC);
  t.skin = skin;
  for (int i = 0; i < e.eyelashes; ++i)
    t.lashes.push_back(
        {e.lid_half_width_mm * (1.7 * u01(rng) - 0.85), 10 + 18 * u01(rng), u01(rng) - 0.3, (u01(rng) - 0.5) * 0.9});
  return t;
}

// A unit complex number in two scalars, its product written out and always inlined: GCC's
// std::complex operator* calls __muldc3 (C99 inf/NaN recovery; these factors are finite), and
// an out-of-line call or a stack array per pixel made the iris loop of the ASan tree (-O1) ten
// times slower than the trigonometric one it replaces.
struct Unit {
  double re, im;
};
// (Not sanitized, like unitPower: see irisTextureAt.)
[[gnu::always_inline, gnu::no_sanitize("address", "undefined")]] inline Unit times(Unit a, Unit b) {
  return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
}

// e^{i n theta} for 0 <= n < 64 from z1 = e^{i theta} and its squares z2 ... z32: no
// trigonometric call. The texture's frequencies are 7 ... 46 (makeTexture).
[[gnu::always_inline, gnu::no_sanitize("address", "undefined")]] inline Unit unitPower(int n, Unit z1, Unit z2, Unit z4,
                                                                                       Unit z8, Unit z16, Unit z32) {
  Unit p{1.0, 0.0};
  if (n & 1) p = times(p, z1);
  if (n & 2) p = times(p, z2);
  if (n & 4) p = times(p, z4);
  if (n & 8) p = times(p, z8);
  if (n & 16) p = times(p, z16);
  if (n & 32) p = times(p, z32);
  return p;
}

// The iris texture's constants for one frame.
struct IrisTexture {
  std::array<int, 6> freq{};
  std::array<Unit, 6> phase{};  // e^{i phi_k}
  std::array<double, 6> amp{};
};

// The texture v = 1 + sum_k a_k sin(f_k theta + phi_k + 3 rho k) at (dx, dy) from the pupil
// centre, theta the polar angle, rho the radius over the iris's mean radius. The f_k are
// integers (makeTexture), so e^{i f_k theta} is a power of e^{i theta} = (dx + i dy) / r and
// e^{i 3 rho k} a power of e^{i 3 rho}: one sincos a pixel instead of an atan2 and six sines (the
// same values to ~1e-15, far below the 8-bit output's step: 1200 frames of both domains
// byte-identical; issue 25: the sines were most of a closed-loop run's CPU).
// Arithmetic on its arguments only (no memory but `tex`'s fixed arrays at indices 0 ... 5), so
// it is left out of the ASan/UBSan instrumentation, which kept its locals in guarded stack slots
// and made it most of the ASan tree's closed-loop time (the helpers it inlines are marked too:
// GCC puts their scope poisoning in before inlining).
[[gnu::no_sanitize("address", "undefined")]] double irisTextureAt(const IrisTexture& tex, double dx, double dy,
                                                                  double rho) {
  const double r = std::sqrt(dx * dx + dy * dy);
  const Unit z1 = r > 0 ? Unit{dx / r, dy / r} : Unit{1.0, 0.0};  // atan2(0, 0) = 0
  const Unit z2 = times(z1, z1), z4 = times(z2, z2), z8 = times(z4, z4), z16 = times(z8, z8);
  const Unit z32 = times(z16, z16);
  const Unit radial{std::cos(3 * rho), std::sin(3 * rho)};
  const int* freq = tex.freq.data();
  const Unit* phase = tex.phase.data();
  const double* amp = tex.amp.data();
  Unit radial_k{1.0, 0.0};
  double v = 1;
  for (int k = 0; k < 6; ++k, radial_k = times(radial_k, radial))
    v += amp[k] * times(times(unitPower(freq[k], z1, z2, z4, z8, z16, z32), phase[k]), radial_k).im;
  return v;
}

void drawIris(cv::Mat& img, cv::Mat& mask, const Layers& l, const EyeAppearance& e, const Texture& t) {
  mask = cv::Mat::zeros(img.size(), CV_8U);  // into the existing buffer (Mat = MatExpr reuses it)
  fillPolygon(mask, l.iris, 255);
  const cv::Rect box =
      cv::boundingRect(std::vector<cv::Point2f>(l.iris.begin(), l.iris.end())) & cv::Rect(0, 0, img.cols, img.rows);
  double mean_r = 0;
  for (const auto& p : l.iris) mean_r += std::hypot(p.x - l.pupil_centre.x, p.y - l.pupil_centre.y);
  mean_r /= static_cast<double>(l.iris.size());
  const double radius = std::max(mean_r, 1.0);
  IrisTexture tex;
  for (std::size_t k = 0; k < 6; ++k) {
    tex.freq[k] = static_cast<int>(t.freq[k]);
    tex.phase[k] = {std::cos(t.phase[k]), std::sin(t.phase[k])};
    tex.amp[k] = t.amp[k];
  }
  // Rows in parallel (each pixel depends on its own coordinates only: the same image whatever the
  // split).
  tbb::parallel_for(tbb::blocked_range<int>(box.y, box.y + box.height, 8), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      float* row = img.ptr<float>(y);
      const auto* m = mask.ptr<std::uint8_t>(y);
      for (int x = box.x; x < box.x + box.width; ++x) {
        if (!m[x]) continue;
        const double dx = x - l.pupil_centre.x, dy = y - l.pupil_centre.y;
        const double rho = std::sqrt(dx * dx + dy * dy) / radius;
        double v = irisTextureAt(tex, dx, dy, rho);
        v *= 1 - 0.35 * std::clamp((rho - 0.8) / 0.2, 0.0, 1.0);  // darker limbal ring
        const double a = m[x] / 255.0;
        row[x] = static_cast<float>((1 - a) * row[x] + a * e.iris_level * v);
      }
    }
  });
}

void drawGlint(cv::Mat& img, const cv::Point2d& p) {
  const int r = 4;
  for (int y = cvFloor(p.y) - r; y <= cvFloor(p.y) + r; ++y) {
    if (y < 0 || y >= img.rows) continue;
    float* row = img.ptr<float>(y);
    for (int x = cvFloor(p.x) - r; x <= cvFloor(p.x) + r; ++x) {
      if (x < 0 || x >= img.cols) continue;
      const double d2 = (x - p.x) * (x - p.x) + (y - p.y) * (y - p.y);
      row[x] += static_cast<float>(1.6 * std::exp(-d2 / (2 * 1.3 * 1.3)));
    }
  }
}

// Adds one sub-frame's radiance to `acc`: the eye (sclera, iris, pupil, glints) inside the soft
// lid opening, `skin` outside it, in the Scratch's `eye` and `opening` images (a closed-loop run
// renders thousands of frames: fresh full-frame images and the temporaries of a matrix
// expression were a fifth of its time in page faults, issue 25). Per pixel the same float
// operations as eye.mul(opening) + skin.mul(1 - opening), so the same image.
void addSubframe(Scratch& s, const EyeAppearance& e, const Layers& l, const Texture& t) {
  cv::Mat &acc = s.acc, &eye = s.eye, &opening = s.opening;
  const cv::Mat& skin = s.skin_scaled;
  eye.setTo(cv::Scalar(e.sclera_level));
  drawIris(eye, s.iris_mask, l, e, t);
  fillPolygon(eye, l.pupil, e.pupil_level);
  for (const auto& g : l.glints) drawGlint(eye, g);
  opening.setTo(cv::Scalar(0));
  fillPolygon(opening, l.opening, 1.0);
  cv::GaussianBlur(opening, opening, {0, 0}, 1.5);  // the lid margin is soft
  for (int y = 0; y < acc.rows; ++y) {
    float* out = acc.ptr<float>(y);
    const float* ey = eye.ptr<float>(y);
    const float* op = opening.ptr<float>(y);
    const float* sk = skin.ptr<float>(y);
    for (int x = 0; x < acc.cols; ++x) {
      const float inside = ey[x] * op[x], outside = sk[x] * (1.0f - op[x]);
      out[x] += inside + outside;
    }
  }
}

void drawLashes(cv::Mat& img, const IrCameraPose& c, const CameraFrame& f, const EyeAppearance& e, const Texture& t) {
  const double w = e.lid_half_width_mm, h = e.lid_half_height_mm;
  for (const auto& lash : t.lashes) {
    const double s = 1 - (lash.x_mm / w) * (lash.x_mm / w);
    const double lower = -0.8 * h * s, upper = 1.1 * h * s;
    const cv::Point2d root = project(
        c, f, {lash.x_mm, lower + std::clamp(e.openness, 0.0, 1.0) * (upper - lower), e.pupil_distance_mm + 1.5});
    // Upper lashes point up and out; those with a positive bend curl down over the opening.
    cv::Point2d p = root;
    double angle = -kPi / 2 + lash.angle;
    for (int seg = 0; seg < 3; ++seg) {
      const cv::Point2d q = p + cv::Point2d(std::cos(angle), std::sin(angle)) * (lash.length_px / 3);
      cv::line(img, cv::Point(cvRound(p.x * 16), cvRound(p.y * 16)), cv::Point(cvRound(q.x * 16), cvRound(q.y * 16)),
               cv::Scalar(0.1), 1, cv::LINE_AA, 4);
      p = q;
      angle += 0.6 * lash.bend * (lash.angle > 0 ? 1 : -1);  // curls outwards, some down over the eye
    }
  }
}

double polygonArea(const std::vector<cv::Point2d>& p) {
  std::vector<cv::Point2f> f(p.begin(), p.end());
  return std::abs(cv::contourArea(f));
}

}  // namespace

std::vector<Eigen::Vector3d> ledRing(const IrCameraPose& camera, int count, double radius_mm) {
  const CameraFrame f = cameraFrame(camera);
  std::vector<Eigen::Vector3d> leds;
  for (int i = 0; i < count; ++i) {
    const double t = 2 * kPi * (i + 0.5) / std::max(count, 1);
    leds.push_back(f.position + radius_mm * (std::cos(t) * f.right + std::sin(t) * f.down));
  }
  return leds;
}

std::array<double, 2> projectToCamera(const IrCameraPose& camera, const Eigen::Vector3d& point_mm) {
  const cv::Point2d p = project(camera, cameraFrame(camera), point_mm);
  return {p.x, p.y};
}

namespace {

// The gaze a fraction `s` of the exposure into a frame (a moving eye sweeps gaze_deg -> gaze_end_deg).
std::array<double, 2> gazeAt(const EyeFrameSpec& spec, double s) {
  if (!spec.moving) return spec.gaze_deg;
  return {spec.gaze_deg[0] + s * (spec.gaze_end_deg[0] - spec.gaze_deg[0]),
          spec.gaze_deg[1] + s * (spec.gaze_end_deg[1] - spec.gaze_deg[1])};
}

EyeFrameTruth frameTruth(const IrCameraPose& c, const EyeAppearance& e, const EyeFrameSpec& spec, Scratch& scratch) {
  const CameraFrame f = cameraFrame(c);
  EyeFrameTruth truth;

  // Ground truth at mid-exposure.
  const Layers mid = eyeLayers(c, f, e, spec, gazeAt(spec, 0.5));
  truth.gaze_deg = gazeAt(spec, 0.5);
  const std::vector<cv::Point2f> outline(mid.pupil.begin(), mid.pupil.end());
  const cv::RotatedRect r = cv::fitEllipse(outline);
  truth.pupil.centre = r.center;
  truth.pupil.major_px = std::max(r.size.width, r.size.height);
  truth.pupil.minor_px = std::min(r.size.width, r.size.height);
  truth.pupil.angle_deg = r.size.width >= r.size.height ? r.angle : r.angle + 90;
  cv::Mat &pupil_mask = scratch.pupil_mask, &open_mask = scratch.open_mask;
  pupil_mask = cv::Mat::zeros(c.size, CV_8U);
  open_mask = cv::Mat::zeros(c.size, CV_8U);
  fillPolygon(pupil_mask, mid.pupil, 255);
  if (polygonArea(mid.opening) > 1) fillPolygon(open_mask, mid.opening, 255);
  cv::threshold(pupil_mask, pupil_mask, 127, 255, cv::THRESH_BINARY);
  cv::threshold(open_mask, open_mask, 127, 255, cv::THRESH_BINARY);
  const double pupil_px = cv::countNonZero(pupil_mask);
  cv::bitwise_and(pupil_mask, open_mask, scratch.visible_mask);
  const double visible_px = cv::countNonZero(scratch.visible_mask);
  truth.visible_fraction = pupil_px > 0 ? visible_px / pupil_px : 0;
  truth.pupil_visible = truth.visible_fraction > 0.05;
  for (const auto& g : mid.glints)
    if (inside(mid.opening, g) && g.x >= 0 && g.y >= 0 && g.x < c.size.width && g.y < c.size.height)
      truth.glints_px.push_back(g);
  return truth;
}

}  // namespace

EyeFrameTruth eyeFrameTruth(const IrCameraPose& c, const EyeAppearance& e, const EyeFrameSpec& spec) {
  const ThreadScratch<Scratch> s;
  return frameTruth(c, e, spec, *s);
}

EyeFrame renderEyeFrame(const IrCameraPose& c, const EyeAppearance& e, const EyeFrameSpec& spec) {
  const CameraFrame f = cameraFrame(c);
  const ThreadScratch<Scratch> lease;
  Scratch& s = *lease;
  const Texture t = makeTexture(c, e, spec.seed, s.skin);
  const int subframes = spec.moving ? std::max(1, spec.blur_subframes) : 1;
  s.acc = cv::Mat::zeros(c.size, CV_32F);  // into the existing buffer (Mat = MatExpr reuses it)
  for (cv::Mat* m : {&s.eye, &s.opening}) m->create(c.size, CV_32F);
  s.skin_scaled = t.skin * e.skin_level;  // into the existing buffer (Mat = MatExpr reuses it)
  for (int i = 0; i < subframes; ++i) {
    const double at = subframes == 1 ? 0.5 : (i + 0.5) / subframes;
    addSubframe(s, e, eyeLayers(c, f, e, spec, gazeAt(spec, at)), t);
  }
  cv::Mat& acc = s.acc;
  acc /= subframes;
  drawLashes(acc, c, f, e, t);
  if (spec.defocus_sigma_px > 0) cv::GaussianBlur(acc, acc, {0, 0}, spec.defocus_sigma_px);
  if (spec.noise_sigma > 0) {
    s.noise.create(c.size, CV_32F);
    cv::RNG rng(spec.seed * 2654435761u + 12345u);
    rng.fill(s.noise, cv::RNG::NORMAL, 0.0, spec.noise_sigma);
    acc += s.noise;
  }
  EyeFrame out;
  acc.convertTo(out.image, CV_8U, 255.0);
  out.truth = frameTruth(c, e, spec, s);
  return out;
}

}  // namespace fovea::gaze
