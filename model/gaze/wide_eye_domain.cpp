#include "model/gaze/wide_eye_domain.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "model/gaze/thread_scratch.h"

namespace fovea::gaze {
namespace {

constexpr double kPi = std::numbers::pi;

struct Draw {
  std::mt19937 rng;
  std::uniform_real_distribution<double> u{0, 1};
  double in(double a, double b) { return a + (b - a) * u(rng); }
  bool chance(double p) { return u(rng) < p; }
  // Uniform over [a, b] without the band [lo, hi] (lo, hi inside [a, b]).
  double outside(double a, double b, double lo, double hi) {
    const double x = in(a, b - (hi - lo));
    return x < lo ? x : x + (hi - lo);
  }
};

struct PostFx {
  double gain = 1, offset = 0;
  double gradient = 0, gradient_dir = 0;  // multiplicative illumination ramp across the frame
  int shadows = 0;
  int stray_glints = 0;
  double edge_glint_chance = 0;  // a stray glint on the pupil outline
  bool partial = false;
};

struct Features {
  bool leds = false, stray = false, motion = false, off_axis = false, partial = false;
  double defocus_max = 1.2;
  double open_lo = 0.85, open_hi = 1.0;
};

Features featuresOf(WideSubset s, Draw& d) {
  Features f;
  switch (s) {
    case WideSubset::Train:
    case WideSubset::TrainPartial:  // train's draws, every frame partial (below)
      f.leds = d.chance(0.6), f.stray = d.chance(0.5), f.motion = d.chance(0.3), f.off_axis = d.chance(0.3);
      f.partial = d.chance(0.12), f.defocus_max = 3.5;
      if (s == WideSubset::TrainPartial) f.partial = true;  // with an open eye: no closed frames
      if (s != WideSubset::TrainPartial && d.chance(0.07))
        f.open_lo = 0, f.open_hi = 0.04;
      else if (d.chance(0.45))
        f.open_lo = 0.15, f.open_hi = 0.85;
      break;
    case WideSubset::Easy:
      break;
    case WideSubset::Glints:
      f.leds = f.stray = true;
      break;
    case WideSubset::Occlusion:
      f.leds = d.chance(0.5), f.open_lo = 0.1, f.open_hi = 0.85;
      break;
    case WideSubset::MotionBlur:
      f.motion = true, f.defocus_max = 3;
      break;
    case WideSubset::OffAxis:
      f.off_axis = true, f.leds = d.chance(0.5);
      break;
    case WideSubset::Partial:
      f.partial = true, f.leds = d.chance(0.5);
      break;
    case WideSubset::Hard:
      f.leds = f.stray = f.motion = true, f.defocus_max = 3, f.open_lo = 0.1, f.open_hi = 0.7;
      break;
    case WideSubset::Closed:
      f.leds = d.chance(0.5), f.stray = d.chance(0.5), f.open_lo = 0, f.open_hi = 0.04;
      break;
    case WideSubset::TrainHard:  // the openness is then bisected to a visible fraction (renderWideFrame)
      f.leds = f.stray = true, f.motion = d.chance(0.7), f.off_axis = d.chance(0.25), f.defocus_max = 3.5;
      break;
  }
  return f;
}

struct WideScene {
  IrCameraPose camera;
  EyeAppearance eye;
  EyeFrameSpec frame;
  PostFx fx;
};

WideScene drawScene(WideSubset subset, int index, std::uint32_t seed, int attempt) {
  std::seed_seq seq{seed, 0x77696465u /* "wide" */, static_cast<std::uint32_t>(subset),
                    static_cast<std::uint32_t>(index), static_cast<std::uint32_t>(attempt)};
  Draw d{std::mt19937(seq)};
  const bool train = isTrainingWideSubset(subset);
  const Features f = featuresOf(subset, d);
  WideScene s;
  s.camera.focal_px = d.in(300, 400);
  s.camera.distance_mm = d.in(28, 42);
  if (f.off_axis) {
    // 20-45 deg off the eye's axis, mostly from below (headset eye cameras).
    const double a = d.in(20, 45), phi = d.in(1.1 * kPi, 1.9 * kPi);
    s.camera.pose_deg = {a * std::cos(phi), a * std::sin(phi)};
  } else {
    s.camera.pose_deg = {d.in(-8, 8), d.in(-12, 4)};
  }
  EyeAppearance& e = s.eye;
  e.pupil_diameter_mm = train ? d.outside(2.5, 8.0, 4.5, 5.0) : d.in(2.5, 8.0);
  e.pupil_distance_mm = d.in(9.5, 11);
  e.iris_radius_mm = d.in(5.5, 6.5);
  e.cornea_radius_mm = d.in(7.4, 8.2);
  e.anterior_chamber_mm = d.in(3.0, 4.0);
  e.lid_half_width_mm = d.in(11, 18);
  e.lid_half_height_mm = d.in(4.5, 8);
  e.openness = d.in(f.open_lo, f.open_hi);
  e.pupil_level = d.in(0.02, 0.2);
  e.iris_level = train ? d.outside(0.25, 0.6, 0.38, 0.46) : d.in(0.25, 0.6);
  e.sclera_level = std::max(e.iris_level + 0.1, d.in(0.55, 0.95));
  e.skin_level = d.in(0.35, 0.8);
  e.eyelashes = static_cast<int>(d.in(0, 120));
  e.corneal_refraction = true;
  EyeFrameSpec& fr = s.frame;
  const double gaze_range = f.off_axis ? 15 : 25;
  fr.gaze_deg = {d.in(-gaze_range, gaze_range), d.in(-0.7 * gaze_range, 0.7 * gaze_range)};
  fr.defocus_sigma_px = d.in(0.4, f.defocus_max);
  fr.noise_sigma = d.in(0.005, 0.05);
  fr.seed = static_cast<std::uint32_t>(d.rng());
  if (f.leds) fr.leds_mm = ledRing(s.camera, 4 + static_cast<int>(d.in(0, 7)), d.in(6, 16));
  if (f.motion) {
    // A saccade during the exposure: 200-700 deg/s over 4-12 ms (main-sequence peak speeds).
    const double speed = d.in(200, 700), exposure = d.in(0.004, 0.012), dir = d.in(0, 2 * kPi);
    fr.moving = true;
    fr.gaze_end_deg = {fr.gaze_deg[0] + speed * exposure * std::cos(dir),
                       fr.gaze_deg[1] + speed * exposure * std::sin(dir)};
  }
  PostFx& fx = s.fx;
  fx.gain = subset == WideSubset::Easy ? d.in(0.7, 1.4) : d.in(0.4, 2.0);
  fx.offset = d.in(-0.03, 0.08);
  fx.gradient = d.in(0, 0.3), fx.gradient_dir = d.in(0, 2 * kPi);
  fx.shadows = subset == WideSubset::Easy ? 0 : static_cast<int>(d.in(0, 2.99));
  if (f.stray) fx.stray_glints = 1 + static_cast<int>(d.in(0, 3.99)), fx.edge_glint_chance = 0.6;
  fx.partial = f.partial;
  return s;
}

// The images kept per thread across frames (thread_scratch.h); each is overwritten before it is read.
struct PostFxScratch {
  cv::Mat img, shade, blob;
};

// Gain, offset, illumination ramp, soft shadows and stray glints on the rendered frame.
void applyPostFx(cv::Mat& grey8, const EyeFrameTruth& truth, const PostFx& fx, std::uint32_t seed) {
  std::mt19937 rng(seed ^ 0x5bd1e995u);
  std::uniform_real_distribution<double> u(0, 1);
  const ThreadScratch<PostFxScratch> scratch;
  cv::Mat &img = scratch->img, &shade = scratch->shade, &blob = scratch->blob;
  grey8.convertTo(img, CV_32F, 1.0 / 255);
  const double cx = img.cols / 2.0, cy = img.rows / 2.0, half = std::max(img.cols, img.rows) / 2.0;
  const double gx = std::cos(fx.gradient_dir), gy = std::sin(fx.gradient_dir);
  shade.create(img.size(), CV_32F);
  for (int y = 0; y < img.rows; ++y) {
    auto* row = shade.ptr<float>(y);
    for (int x = 0; x < img.cols; ++x)
      row[x] = static_cast<float>(1 + fx.gradient * ((x - cx) * gx + (y - cy) * gy) / half);
  }
  for (int i = 0; i < fx.shadows; ++i) {
    blob = cv::Mat::zeros(img.size(), CV_32F);  // into the existing buffer
    const cv::Point2f c(static_cast<float>(u(rng) * img.cols), static_cast<float>(u(rng) * img.rows));
    const cv::Size2f axes(static_cast<float>(40 + 120 * u(rng)), static_cast<float>(20 + 60 * u(rng)));
    cv::ellipse(blob, cv::RotatedRect(c, axes * 2.0f, static_cast<float>(180 * u(rng))), cv::Scalar(1), -1);
    cv::GaussianBlur(blob, blob, {0, 0}, 10 + 20 * u(rng));
    shade = shade.mul(1.0 - (0.15 + 0.35 * u(rng)) * blob);
  }
  img = img.mul(shade) * fx.gain + fx.offset;
  for (int i = 0; i < fx.stray_glints; ++i) {
    cv::Point2d p(u(rng) * img.cols, u(rng) * img.rows);
    if (truth.pupil_visible && u(rng) < fx.edge_glint_chance) {  // on the outline
      const double t = 2 * kPi * u(rng), a = truth.pupil.angle_deg * kPi / 180;
      const double ex = truth.pupil.major_px / 2 * std::cos(t), ey = truth.pupil.minor_px / 2 * std::sin(t);
      p = truth.pupil.centre + cv::Point2d(ex * std::cos(a) - ey * std::sin(a), ex * std::sin(a) + ey * std::cos(a));
    }
    const double sigma = 0.8 + 1.7 * u(rng), amp = 0.6 + 1.0 * u(rng);
    const int r = static_cast<int>(std::ceil(3 * sigma));
    for (int y = std::max(0, cvFloor(p.y) - r); y <= std::min(img.rows - 1, cvFloor(p.y) + r); ++y)
      for (int x = std::max(0, cvFloor(p.x) - r); x <= std::min(img.cols - 1, cvFloor(p.x) + r); ++x) {
        const double d2 = (x - p.x) * (x - p.x) + (y - p.y) * (y - p.y);
        img.at<float>(y, x) += static_cast<float>(amp * std::exp(-d2 / (2 * sigma * sigma)));
      }
  }
  img.convertTo(grey8, CV_8U, 255.0);
}

// A partial frame: the sensor window shifted (the principal point moved) so that the pupil's
// centre lies within a pupil radius of one of the frame's edges; the visible fraction also
// leaves out the part of the pupil outside the frame.
EyeFrame renderPartial(const WideScene& s, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const cv::Size frame = s.camera.size;
  const EyeFrameTruth centred = eyeFrameTruth(s.camera, s.eye, s.frame);
  const cv::Point2d c = centred.pupil.centre;
  const double r = centred.pupil.major_px / 2;
  const int edge = static_cast<int>(u(rng) * 4) % 4;
  const double along = 60 + u(rng) * (frame.width - 120), inset = 2 + u(rng) * r;
  cv::Point2d target;  // where the centre lands in the frame
  if (edge == 0) target = {inset, along};
  if (edge == 1) target = {frame.width - inset, along};
  if (edge == 2) target = {along, inset};
  if (edge == 3) target = {along, frame.height - inset};
  IrCameraPose shifted = s.camera;
  shifted.principal_offset_px = {target.x - c.x, target.y - c.y};
  EyeFrame f = renderEyeFrame(shifted, s.eye, s.frame);
  cv::Mat inside = cv::Mat::zeros(frame, CV_8U);
  const auto& p = f.truth.pupil;
  cv::ellipse(
      inside,
      cv::RotatedRect(cv::Point2f(p.centre), cv::Size2f(static_cast<float>(p.major_px), static_cast<float>(p.minor_px)),
                      static_cast<float>(p.angle_deg)),
      cv::Scalar(255), -1);
  const double area = std::numbers::pi / 4 * p.major_px * p.minor_px;  // of the whole ellipse
  f.truth.visible_fraction *= area > 0 ? std::min(1.0, cv::countNonZero(inside) / area) : 0;
  f.truth.pupil_visible = f.truth.visible_fraction > 0.05;
  return f;
}

bool accepted(WideSubset s, const EyeFrameTruth& t) {
  switch (s) {
    case WideSubset::Occlusion:
      return t.visible_fraction >= 0.3 && t.visible_fraction <= 0.9;
    case WideSubset::Hard:
      return t.visible_fraction >= 0.3 && t.visible_fraction <= 0.5;
    case WideSubset::TrainHard:
      return t.visible_fraction >= 0.15 && t.visible_fraction <= 0.7;
    case WideSubset::Closed:
      return !t.pupil_visible;
    case WideSubset::Train:
      return true;
    default:
      return t.pupil_visible;
  }
}

}  // namespace

const char* wideSubsetName(WideSubset s) {
  switch (s) {
    case WideSubset::Train:
      return "train";
    case WideSubset::Easy:
      return "easy";
    case WideSubset::Glints:
      return "glints";
    case WideSubset::Occlusion:
      return "occlusion";
    case WideSubset::MotionBlur:
      return "motion_blur";
    case WideSubset::OffAxis:
      return "off_axis";
    case WideSubset::Partial:
      return "partial";
    case WideSubset::Hard:
      return "hard";
    case WideSubset::Closed:
      return "closed";
    case WideSubset::TrainHard:
      return "train_hard";
    case WideSubset::TrainPartial:
      return "train_partial";
  }
  return "?";
}

std::vector<WideSubset> allWideSubsets() {
  std::vector<WideSubset> all;
  for (int i = 0; i <= static_cast<int>(WideSubset::TrainPartial); ++i) all.push_back(static_cast<WideSubset>(i));
  return all;
}

std::optional<WideSubset> parseWideSubset(const std::string& name) {
  for (WideSubset s : allWideSubsets())
    if (name == wideSubsetName(s)) return s;
  return std::nullopt;
}

bool isTrainingWideSubset(WideSubset s) {
  return s == WideSubset::Train || s == WideSubset::TrainHard || s == WideSubset::TrainPartial;
}

std::vector<WideSubset> heldOutWideSubsets() {
  std::vector<WideSubset> held;
  for (WideSubset s : allWideSubsets())
    if (!isTrainingWideSubset(s)) held.push_back(s);
  return held;
}

EyeFrame renderWideFrame(WideSubset subset, int index, std::uint32_t seed) {
  // Occlusion and hard frames: a wanted visible fraction, reached by bisecting the lid's
  // openness on the ground truth alone (the visible fraction grows with the openness); a
  // scene whose pupil is under the lids even when open is drawn again. Closed frames (and
  // the rare others without a visible pupil) are drawn again until they fit. Seeded.
  const bool cover = subset == WideSubset::Occlusion || subset == WideSubset::Hard || subset == WideSubset::TrainHard;
  EyeFrame f;
  for (int attempt = 0; attempt < 60; ++attempt) {
    WideScene s = drawScene(subset, index, seed, attempt);
    std::mt19937 rng(s.frame.seed);
    if (cover && !s.fx.partial) {
      const auto [want_lo, want_hi] = subset == WideSubset::Hard        ? std::pair(0.3, 0.5)
                                      : subset == WideSubset::TrainHard ? std::pair(0.2, 0.65)
                                                                        : std::pair(0.3, 0.9);
      const double target = std::uniform_real_distribution<double>(want_lo, want_hi)(rng);
      s.eye.openness = 1;
      if (eyeFrameTruth(s.camera, s.eye, s.frame).visible_fraction < target) continue;
      double lo = 0, hi = 1;
      for (int it = 0; it < 12; ++it) {
        s.eye.openness = 0.5 * (lo + hi);
        (eyeFrameTruth(s.camera, s.eye, s.frame).visible_fraction < target ? lo : hi) = s.eye.openness;
      }
      s.eye.openness = 0.5 * (lo + hi);
    }
    f = s.fx.partial ? renderPartial(s, rng) : renderEyeFrame(s.camera, s.eye, s.frame);
    if (!accepted(subset, f.truth) && attempt + 1 < 60) continue;
    applyPostFx(f.image, f.truth, s.fx, s.frame.seed);
    return f;
  }
  return f;
}

}  // namespace fovea::gaze
