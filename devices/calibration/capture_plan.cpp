#include "devices/calibration/capture_plan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "model/analysis/gaze_studies.h"
#include "model/analysis/hoe_travel.h"
#include "model/analysis/trace_evaluator.h"
#include "model/io/json_fields.h"

namespace fovea::devices {

namespace {

std::string gazeTag(std::array<double, 2> g) {
  char buf[64];
  if (g[1] == 0.0)
    std::snprintf(buf, sizeof buf, "yaw%+g", g[0]);
  else
    std::snprintf(buf, sizeof buf, "yaw%+g_pitch%+g", g[0], g[1]);
  return buf;
}

// Targets for a gaze: camera, HOE and micro-OLED coordinates the scene binds.
void addTarget(const Scene& scene, std::vector<StageTarget>& out, const std::string& element, const std::string& axis,
               double value) {
  if (isBound(scene, element, axis)) out.push_back({element, axis, value});
}

std::vector<StageTarget> cameraTargets(const Scene& scene, std::array<double, 2> gaze) {
  std::vector<StageTarget> t;
  addTarget(scene, t, "camera", "yaw", gaze[0]);
  addTarget(scene, t, "camera", "pitch", gaze[1]);
  return t;
}

bool allWithin(const Scene& scene, const std::vector<StageTarget>& ts, std::string* why) {
  for (const auto& t : ts)
    if (!withinSoftLimits(scene, t)) {
      if (why) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "%s.%s = %.3f is outside the soft limits", t.element.c_str(), t.axis.c_str(),
                      t.value);
        *why = buf;
      }
      return false;
    }
  return true;
}

}  // namespace

const char* toString(CaptureKind k) {
  switch (k) {
    case CaptureKind::Geometric:
      return "geometric";
    case CaptureKind::Color:
      return "color";
    case CaptureKind::Gaze:
      return "gaze";
  }
  return "geometric";
}

std::optional<CaptureKind> captureKindFromString(const std::string& s) {
  if (s == "geometric") return CaptureKind::Geometric;
  if (s == "color" || s == "colour") return CaptureKind::Color;
  if (s == "gaze") return CaptureKind::Gaze;
  return std::nullopt;
}

bool isBound(const Scene& scene, const std::string& element, const std::string& axis) {
  for (const auto& b : scene.stages)
    if (b.element == element && b.axis == axis) return true;
  return false;
}

bool withinSoftLimits(const Scene& scene, const StageTarget& t) {
  for (const auto& b : scene.stages)
    if (b.element == t.element && b.axis == t.axis)
      return t.value >= b.soft_limits[0] - 1e-9 && t.value <= b.soft_limits[1] + 1e-9;
  return true;
}

nlohmann::json toJson(const CaptureStep& s) {
  nlohmann::json targets = nlohmann::json::array();
  for (const auto& t : s.targets) targets.push_back({{"element", t.element}, {"axis", t.axis}, {"value", t.value}});
  return {{"id", s.id},
          {"kind", toString(s.kind)},
          {"display", toString(s.display)},
          {"gaze_deg", s.gaze_deg},
          {"targets", targets},
          {"pattern", image::toJson(s.pattern)},
          {"instruction", s.instruction}};
}

CaptureStep captureStepFromJson(const nlohmann::json& j, const std::string& path) {
  // Typed fields with their JSON path in every message (model/io/json_fields.h).
  const JsonFields f(j, "", path);
  CaptureStep s;
  s.id = f.text("id", {}, std::nullopt, true);
  const auto kind = captureKindFromString(f.text("kind"));
  if (!kind) f.fail(f.at("kind"), "unknown kind \"" + j["kind"].get<std::string>() + "\"");
  s.kind = *kind;
  s.display = f.text("display", {"peripheral", "foveal"}) == "foveal" ? BenchDisplay::Foveal : BenchDisplay::Peripheral;
  const auto gaze = f.numbers("gaze_deg", Range::closed(-90, 90), 2);
  s.gaze_deg = {gaze[0], gaze[1]};
  for (const JsonFields& t : f.objects("targets", true, 64))
    s.targets.push_back({t.text("element"), t.text("axis"), t.number("value", Range::any())});
  f.get("pattern", true);
  try {
    s.pattern = image::patternFromJson(j["pattern"]);
  } catch (const std::exception&) {
    f.fail(f.at("pattern"), "not a display pattern (docs/calibration.md)");
  }
  s.instruction = f.text("instruction", {}, std::string());
  return s;
}

std::function<std::array<double, 2>(std::array<double, 2>)> analysedHoeShift(const Scene& scene) {
  return [scene](std::array<double, 2> g) { return hoeTravel(scene, g, sceneXpRule(scene)).shift_mm; };
}

image::DisplayPattern peripheralBoard(const Scene& scene, std::array<double, 2> gaze, std::array<int, 2> squares,
                                      double size) {
  const auto region = projectorRegionOnHoe(scene, static_cast<double>(squares[0]) / squares[1], 5.0);
  const double hw = 0.5 * size * (region[2] - region[0]), hh = 0.5 * size * (region[3] - region[1]);
  Eigen::Vector2d c(0.5 * (region[0] + region[2]), 0.5 * (region[1] + region[3]));
  if (const auto los = projectorPixelOnLineOfSight(scene, gaze)) {
    c.x() = std::clamp(los->x(), region[0] + hw, region[2] - hw);
    c.y() = std::clamp(los->y(), region[1] + hh, region[3] - hh);
  }
  return image::checkerboardInRect({c.x() - hw, c.y() - hh, c.x() + hw, c.y() + hh}, squares, 0.5);
}

image::DisplayPattern fovealBoard(const Scene& scene, std::array<int, 2> squares, double fill) {
  return image::centredCheckerboard(scene.foveal_display.pixels, squares, fill);
}

Plan geometricPlan(const Scene& scene, const GeometricPlanOptions& o) {
  Plan plan;
  std::vector<double> gazes = o.gazes_yaw_deg;
  if (gazes.empty()) {
    const double lo = scene.eye.gaze_range_deg[0], hi = scene.eye.gaze_range_deg[1];
    for (int i = 0; i < 5; ++i) gazes.push_back(lo + (hi - lo) * i / 4.0);
  }
  const auto hoe_shift =
      o.hoe_shift ? o.hoe_shift : [&scene](std::array<double, 2> g) { return geometricHoeShiftForGaze(scene, g); };
  for (double yaw : gazes) {
    const std::array<double, 2> gaze{yaw, 0.0};
    const std::string tag = gazeTag(gaze);
    const std::vector<StageTarget> camera = cameraTargets(scene, gaze);
    std::string why;
    if (!allWithin(scene, camera, &why)) {
      plan.skipped.push_back("gaze " + tag + ": " + why);
      continue;
    }
    const auto xp = hoe_shift(gaze);
    const auto xf = fovealShiftForGaze(scene, gaze);
    std::vector<StageTarget> hoe, foveal;
    addTarget(scene, hoe, "hoe", "x", xp[0]);
    addTarget(scene, hoe, "hoe", "y", xp[1]);
    addTarget(scene, foveal, "foveal_display", "x", xf[0]);
    addTarget(scene, foveal, "foveal_display", "y", xf[1]);
    const bool hoe_ok = allWithin(scene, hoe, &why);
    if (!hoe_ok) plan.skipped.push_back("peripheral at " + tag + ": " + why);
    const bool foveal_ok = allWithin(scene, foveal, &why);
    if (!foveal_ok) plan.skipped.push_back("foveal at " + tag + ": " + why);
    // One pose per gaze: every reachable element goes to its target.
    std::vector<StageTarget> pose = camera;
    if (hoe_ok) pose.insert(pose.end(), hoe.begin(), hoe.end());
    if (foveal_ok) pose.insert(pose.end(), foveal.begin(), foveal.end());
    if (hoe_ok) {
      CaptureStep s;
      s.id = "geometric/peripheral/" + tag;
      s.kind = CaptureKind::Geometric;
      s.display = BenchDisplay::Peripheral;
      s.gaze_deg = gaze;
      s.targets = pose;
      s.pattern = peripheralBoard(scene, gaze, o.peripheral_squares, o.peripheral_size);
      s.instruction = "Projector shows the checkerboard, micro-OLED off; HOE at x_p for gaze " + tag;
      plan.steps.push_back(s);
    }
    if (foveal_ok) {
      CaptureStep s;
      s.id = "geometric/foveal/" + tag;
      s.kind = CaptureKind::Geometric;
      s.display = BenchDisplay::Foveal;
      s.gaze_deg = gaze;
      s.targets = pose;
      s.pattern = fovealBoard(scene, o.foveal_squares, o.foveal_fill);
      s.instruction = "Micro-OLED shows the checkerboard, projector off; micro-OLED at x_f for gaze " + tag;
      plan.steps.push_back(s);
    }
  }
  return plan;
}

Plan colorPlan(const Scene& scene, std::vector<double> levels) {
  Plan plan;
  const std::vector<StageTarget> pose = [&] {
    std::vector<StageTarget> t = cameraTargets(scene, {0, 0});
    addTarget(scene, t, "hoe", "x", 0.0);
    addTarget(scene, t, "hoe", "y", 0.0);
    addTarget(scene, t, "foveal_display", "x", 0.0);
    addTarget(scene, t, "foveal_display", "y", 0.0);
    return t;
  }();
  const char* channel_names[3] = {"R", "G", "B"};
  for (BenchDisplay d : {BenchDisplay::Foveal, BenchDisplay::Peripheral}) {
    auto add = [&](const std::string& name, std::array<double, 3> rgb) {
      CaptureStep s;
      s.id = std::string("color/") + toString(d) + "/" + name;
      s.kind = CaptureKind::Color;
      s.display = d;
      s.targets = pose;
      s.pattern = image::flatPatch(rgb);
      char buf[96];
      std::snprintf(buf, sizeof buf, "%s display: patch RGB %.0f %.0f %.0f — measure it with the spectroradiometer",
                    toString(d), rgb[0] * 255, rgb[1] * 255, rgb[2] * 255);
      s.instruction = buf;
      plan.steps.push_back(s);
    };
    add("black", {0, 0, 0});
    for (int c = 0; c < 3; ++c)
      for (double level : levels) {
        std::array<double, 3> rgb{0, 0, 0};
        rgb[c] = level;
        char name[32];
        std::snprintf(name, sizeof name, "%s%03d", channel_names[c], static_cast<int>(std::lround(level * 255)));
        add(name, rgb);
      }
    add("white", {1, 1, 1});
  }
  return plan;
}

Plan gazePlan(const Scene& scene, double offset_deg) {
  Plan plan;
  const std::array<std::pair<const char*, std::array<double, 2>>, 5> points{{{"centre", {0, 0}},
                                                                             {"left", {-offset_deg, 0}},
                                                                             {"right", {offset_deg, 0}},
                                                                             {"up", {0, offset_deg}},
                                                                             {"down", {0, -offset_deg}}}};
  const auto& px = scene.foveal_display.pixels;
  for (const auto& [name, gaze] : points) {
    std::vector<StageTarget> t = cameraTargets(scene, gaze);
    const auto xf = fovealShiftForGaze(scene, gaze);
    addTarget(scene, t, "foveal_display", "x", xf[0]);
    addTarget(scene, t, "foveal_display", "y", xf[1]);
    std::string why;
    if (!allWithin(scene, t, &why)) {
      plan.skipped.push_back(std::string("gaze point ") + name + ": " + why);
      continue;
    }
    CaptureStep s;
    s.id = std::string("gaze/") + name;
    s.kind = CaptureKind::Gaze;
    s.display = BenchDisplay::Foveal;
    s.gaze_deg = gaze;
    s.targets = t;
    s.pattern = image::fixationDot({0.5 * (px[0] - 1), 0.5 * (px[1] - 1)}, 0.02 * px[1]);
    s.instruction = std::string("Fixation target ") + name + ": the subject looks at the dot";
    plan.steps.push_back(s);
  }
  return plan;
}

}  // namespace fovea::devices
