// fovea-cli track IMAGE... | --virtual N [--domain classic|wide] [--seed S]
//                 [--detector classical|learned|auto] [--auto-radius-px R] [--refine-scale-above F] [--json]
// Pupil detection on IR eye-camera frames (model/gaze/pupil_detector_choice.h: the classical
// detector by default, the learned one or both fused): per frame the pupil centre, ellipse,
// glints, confidence and the detector's time. Images are read by the
// project's image I/O (PNG, JPEG, TIFF, ...) and taken as the camera's 8-bit grey levels.
// --virtual N renders N synthetic frames by seed (model/gaze/pupil_benchmark.h, cycling
// through the easy, glints, occlusion, motion-blur, off-axis and closed-eye subsets) and
// adds the ground truth and the errors; --domain wide draws them from the wide randomised
// domain's held-out subsets instead (model/gaze/wide_eye_domain.h: easy, glints, occlusion,
// motion_blur, off_axis, partial, hard, closed). Per subset the centre error's percentiles
// count a missed pupil as an infinite error (null when more than that share is missed). An unreadable image gives a
// frame with zero confidence and its error, the others are still tracked; the exit code is then 1.
// --auto-radius-px R sets auto's acceptance radius (pupil_detector_choice.h: kAutoAcceptRadiusPx,
// 2 frame px; 0 gives the learned centres, a huge R every classical fit near them, which
// scripts/auto-radius-sweep.py uses to choose R); the JSON names it as auto_accept_radius_px.
// --refine-scale-above F sets where the learned detector's refining window starts to scale with
// the pupil (learned_pupil_detector.h: kRefineScaleAboveMajor, a fraction of the window's span;
// 0: never), which scripts/refine-scale-sweep.py uses to choose F; the JSON names it as
// refine_scale_above for the learned and auto detectors.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>

#include <opencv2/imgproc.hpp>

#include "app/cli/cli_common.h"
#include "app/cli/detector_option.h"
#include "model/color/srgb.h"
#include "model/gaze/pupil_benchmark.h"
#include "model/gaze/pupil_detector.h"
#include "model/gaze/pupil_detector_choice.h"
#include "model/gaze/wide_eye_domain.h"
#include "model/image/image_io.h"

namespace fovea::cli {
namespace cmd_track {  // one per command file: fovea-cli compiles in unity batches
namespace {

nlohmann::json point(const cv::Point2d& p) {
  return {p.x, p.y};
}

nlohmann::json ellipseJson(const gaze::EyeEllipse& e) {
  return {
      {"centre_px", point(e.centre)}, {"major_px", e.major_px}, {"minor_px", e.minor_px}, {"angle_deg", e.angle_deg}};
}

// The file's grey levels: the image I/O returns linear light, re-encoded here to the sRGB
// values a camera writes.
cv::Mat readGrey8(const std::string& path) {
  const cv::Mat rgb = image::readLinearRgb(path);
  cv::Mat grey(rgb.size(), CV_8U);
  for (int y = 0; y < rgb.rows; ++y) {
    const auto* p = rgb.ptr<cv::Vec3f>(y);
    auto* g = grey.ptr<std::uint8_t>(y);
    for (int x = 0; x < rgb.cols; ++x) {
      const float lin = 0.2126f * p[x][0] + 0.7152f * p[x][1] + 0.0722f * p[x][2];  // Rec. 709 luminance
      g[x] = cv::saturate_cast<std::uint8_t>(255.0f * color::linearToSrgb(lin));
    }
  }
  return grey;
}

// The q-quantile (nearest rank) of the errors; NaN (JSON null) when it is a missed frame.
double percentile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size()))) - 1;
  const double x = v[std::min(k, v.size() - 1)];
  return std::isfinite(x) ? x : std::numeric_limits<double>::quiet_NaN();
}

nlohmann::json detectionJson(const gaze::PupilDetection& d, double ms) {
  nlohmann::json glints = nlohmann::json::array();
  for (const auto& g : d.glints_px) glints.push_back(point(g));
  nlohmann::json j{{"found", d.found},
                   {"confidence", d.confidence},
                   {"centre_px", d.found ? point(d.ellipse.centre) : nlohmann::json(nullptr)},
                   {"ellipse", d.found ? ellipseJson(d.ellipse) : nlohmann::json(nullptr)},
                   {"glints_px", glints},
                   {"time_ms", ms}};
  if (!d.found) j["reason"] = d.reason;
  return j;
}

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("track", "Detect the pupil in IR eye-camera frames (files or synthetic)");
  struct Args {
    std::vector<std::string> images;
    int virtual_frames = 0;
    unsigned seed = 1;
    bool json = false;
    std::string detector = "classical", domain = "classic";
    double auto_radius_px = gaze::kAutoAcceptRadiusPx;
    double refine_scale_above = gaze::kRefineScaleAboveMajor;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("IMAGE", a->images, "eye-camera images (PNG, JPEG, ...)");
  auto* v = cmd->add_option("--virtual", a->virtual_frames, "track N synthetic frames with ground truth")
                ->check(CLI::Range(1, 100000));
  addSeedOption(cmd, a->seed, "seed of the synthetic frames (default 1)");
  cmd->add_flag("--json", a->json, "print the result as JSON");
  cmd->add_option("--detector", a->detector, "classical (default), learned or auto (learned refined by classical)");
  auto* radius = cmd->add_option("--auto-radius-px", a->auto_radius_px,
                                 "--detector auto: take the classical fit when its centre is within R frame px of "
                                 "the learned one (default 2; 0: never)");
  auto* scale = cmd->add_option("--refine-scale-above", a->refine_scale_above,
                                "--detector learned|auto: scale the refining window with a pupil whose proposed "
                                "major axis exceeds F of the window's span (192 px of a 400 px frame; 0: never)");
  cmd->add_option("--domain", a->domain, "--virtual frames: classic (default, the pupil benchmark) or wide");
  cmd->callback([a, v, radius, scale] {
    const bool virt = v->count() > 0;
    if (virt == !a->images.empty()) usageError("track: give either IMAGE files or --virtual N");
    if (a->domain != "classic" && a->domain != "wide")
      usageError("--domain: '" + a->domain + "' is not one of classic, wide");
    if (!virt && a->domain != "classic") usageError("--domain: only with --virtual");
    const bool wide = a->domain == "wide";
    if (!(a->auto_radius_px >= 0)) usageError("--auto-radius-px: a radius >= 0 frame px");
    const gaze::PupilDetectorKind kind = detectorOrExit(a->detector);
    if (radius->count() > 0 && kind != gaze::PupilDetectorKind::Auto)
      usageError("--auto-radius-px: only with --detector auto");
    if (!(a->refine_scale_above >= 0 && a->refine_scale_above <= 1))
      usageError("--refine-scale-above: a fraction of the window's span in [0, 1] (0: never scale)");
    if (scale->count() > 0 && kind == gaze::PupilDetectorKind::Classical)
      usageError("--refine-scale-above: only with --detector learned or auto");
    const gaze::PupilDetectorOptions options;
    nlohmann::json frames = nlohmann::json::array();
    double total_ms = 0, max_ms = 0;
    int found = 0, unreadable = 0;
    gaze::SubsetScore score;
    score.subset = "all";
    std::map<std::string, gaze::SubsetScore> per_subset;
    std::map<std::string, double> subset_ms;
    std::map<std::string, std::vector<double>> errors;  // per subset, frames with a pupil (missed: inf)
    std::string first_error;
    const auto timed = [&](const cv::Mat& img, gaze::PupilDetection& d) {
      const auto t0 = std::chrono::steady_clock::now();
      d = gaze::detectPupilWith(kind, img, options, gaze::kLearnedMinConfidence, a->auto_radius_px,
                                a->refine_scale_above);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      total_ms += ms;
      max_ms = std::max(max_ms, ms);
      found += d.found ? 1 : 0;
      return ms;
    };
    const int n = virt ? a->virtual_frames : static_cast<int>(a->images.size());
    for (int i = 0; i < n; ++i) {
      gaze::PupilDetection d;
      nlohmann::json f;
      if (virt) {
        std::string subset_name;
        gaze::EyeFrame frame;
        if (wide) {
          const auto subsets = gaze::heldOutWideSubsets();
          const gaze::WideSubset subset = subsets[static_cast<std::size_t>(i) % subsets.size()];
          frame = gaze::renderWideFrame(subset, i / static_cast<int>(subsets.size()), a->seed);
          subset_name = gaze::wideSubsetName(subset);
        } else {
          const auto subsets = gaze::allSubsets();
          const gaze::EyeSubset subset = subsets[i % subsets.size()];
          frame = gaze::renderBenchmarkFrame(subset, i / static_cast<int>(subsets.size()), a->seed);
          subset_name = gaze::subsetName(subset);
        }
        const double ms = timed(frame.image, d);
        subset_ms[subset_name] += ms;
        f = detectionJson(d, ms);
        const gaze::FrameScore s = gaze::scoreDetection(frame.truth, d);
        score.add(s);
        per_subset[subset_name].add(s);
        if (s.truth_visible)
          errors[subset_name].push_back(s.found ? s.centre_error_px : std::numeric_limits<double>::infinity());
        f["subset"] = subset_name;
        f["truth"] = {{"pupil_visible", frame.truth.pupil_visible},
                      {"visible_fraction", frame.truth.visible_fraction},
                      {"centre_px", point(frame.truth.pupil.centre)},
                      {"ellipse", ellipseJson(frame.truth.pupil)},
                      {"gaze_deg", {frame.truth.gaze_deg[0], frame.truth.gaze_deg[1]}}};
        if (s.truth_visible && s.found)
          f["error"] = {{"centre_px", s.centre_error_px}, {"axes_px", s.axis_error_px}, {"within_5px", s.within_5px}};
        else
          f["error"] = {{"false_positive", !s.truth_visible && s.found}, {"missed", s.truth_visible && !s.found}};
      } else {
        const std::string& path = a->images[static_cast<std::size_t>(i)];
        cv::Mat img;
        std::string error;
        try {
          img = readGrey8(path);
        } catch (const std::exception& e) {
          error = e.what();
        }
        if (error.empty()) {
          const double ms = timed(img, d);
          f = detectionJson(d, ms);
        } else {
          ++unreadable;
          if (first_error.empty()) first_error = error;
          d.reason = "unreadable image";
          f = detectionJson(d, 0);
          f["error"] = error;
        }
        f["image"] = path;
      }
      f["index"] = i;
      frames.push_back(f);
    }
    nlohmann::json summary{
        {"frames", n}, {"found", found}, {"mean_time_ms", n ? total_ms / n : 0}, {"max_time_ms", max_ms}};
    if (virt) {
      score.finish();
      summary["with_pupil"] = score.with_pupil;
      summary["detection_rate"] = score.detection_rate;
      summary["mean_centre_error_px"] = score.mean_centre_error_px;
      summary["mean_axis_error_px"] = score.mean_axis_error_px;
      summary["false_positives"] = score.false_positives;
      nlohmann::json subsets = nlohmann::json::array();
      for (auto& [name, sc] : per_subset) {
        sc.finish();
        subsets.push_back({{"subset", name},
                           {"frames", sc.frames},
                           {"with_pupil", sc.with_pupil},
                           {"found", sc.found},
                           {"detection_rate", sc.detection_rate},
                           {"mean_centre_error_px", sc.mean_centre_error_px},
                           {"mean_axis_error_px", sc.mean_axis_error_px},
                           {"false_positives", sc.false_positives},
                           {"false_positive_rate", sc.false_positive_rate},
                           {"centre_error_px_p50", percentile(errors[name], 0.50)},
                           {"centre_error_px_p90", percentile(errors[name], 0.90)},
                           {"centre_error_px_p95", percentile(errors[name], 0.95)},
                           {"mean_time_ms", sc.frames ? subset_ms[name] / sc.frames : 0.0}});
      }
      summary["subsets"] = subsets;
    } else {
      summary["unreadable"] = unreadable;
    }
    nlohmann::json out{{"source", virt ? "virtual" : "images"},
                       {"detector", gaze::detectorName(kind)},
                       {"domain", virt ? nlohmann::json(a->domain) : nlohmann::json(nullptr)},
                       {"seed", virt ? nlohmann::json(a->seed) : nlohmann::json(nullptr)},
                       {"frames", frames},
                       {"summary", summary}};
    if (kind != gaze::PupilDetectorKind::Classical) {  // which network files ran (null: no refining stage)
      const auto files = gaze::learnedModelFiles();
      out["detector_model"] = files.model;
      out["detector_refine_model"] = files.refine.empty() ? nlohmann::json(nullptr) : nlohmann::json(files.refine);
      out["refine_scale_above"] = a->refine_scale_above;
    }
    if (kind == gaze::PupilDetectorKind::Auto) out["auto_accept_radius_px"] = a->auto_radius_px;
    if (a->json)
      printJson(out);
    else
      std::cout << "tracked " << n << " frames: pupil found in " << found << ", mean " << summary["mean_time_ms"]
                << " ms per frame\n";
    if (unreadable) inputError(first_error);
  });
}

const Registrar reg{"track", &install};

}  // namespace
}  // namespace cmd_track
}  // namespace fovea::cli
