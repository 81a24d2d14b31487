// fovea-cli closed-loop SCENE --saccades N --seed S [--stage-model M] [--fps F]
//                         [--latency-sweep MS,...] [--json]
// The closed gaze loop on the virtual bench (devices/bench/closed_gaze_loop.h): rendered
// eye-camera frames -> pupil detector -> C.4 calibration map -> HOE and micro-OLED stages
// following the gaze through a main-sequence saccade sequence. Reports the latency budget
// (capture, detect, map, command, stage motion), the foveal inset's error and the FOV lost
// while the HOE is in transit; --latency-sweep repeats the stage simulation with extra
// latency added before the command (the same tracked frames).
//
// fovea-cli closed-loop SCENE --binocular --fixations FILE|N [--ipd MM] [--seed S]
//                         [--stage-model M] [--focus-stage-model M] [--fps F]
//                         [--detector classical|learned|auto] [--json]
// The binocular loop with focus (devices/bench/binocular_loop.h): both eyes, each on its own
// train (a binocular scene's left train; the mirror image of a monocular scene's), fixate
// points in depth and direction; vergence from both trackers (each
// calibrated and tracking with --detector) drives the focus stages. FILE: {"fixations": [{"distance_cm",
// "direction_deg": [yaw, pitch] or yaw, "hold_ms"}]}; N: that many random fixations (30-250 cm) drawn with the seed.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <iostream>
#include <limits>

#include "app/cli/cli_common.h"
#include "app/cli/detector_option.h"
#include "devices/bench/binocular_loop.h"
#include "devices/bench/closed_gaze_loop.h"
#include "model/gaze/eye_tracker_calibration.h"
#include "model/io/json_fields.h"
#include "model/io/json_input.h"

namespace fovea::cli {
namespace cmd_closed_loop {  // one per command file: fovea-cli compiles in unity batches
namespace {

// Mean, 95th percentile and maximum; null when there were no values (e.g. no saccade settled).
nlohmann::json statsJson(const devices::Stats& s, double scale = 1) {
  if (s.count == 0) return {{"mean", nullptr}, {"p95", nullptr}, {"max", nullptr}};
  return {{"mean", s.mean * scale}, {"p95", s.p95 * scale}, {"max", s.max * scale}};
}

nlohmann::json resultJson(const devices::ClosedLoopResult& r) {
  const double ms = 1000;
  std::vector<double> amp, vel, dur;
  for (const auto& s : r.saccades) {
    amp.push_back(s.amplitude_deg);
    vel.push_back(s.peak_velocity_deg_s);
    dur.push_back(s.duration_s);
  }
  const double d = std::max(r.duration_s, 1e-12);
  return {
      {"latency_budget_ms",
       {{"capture", r.capture_s * ms},
        {"detect", r.detect_s * ms},
        {"detect_measured_mean", r.detect_measured_mean_s * ms},
        {"detect_measured_max", r.detect_measured_max_s * ms},
        {"map", r.map_s * ms},
        {"extra", r.extra_latency_s * ms},
        {"command", r.command_s * ms},
        {"to_command", r.latency_to_command_s * ms},
        {"hoe_motion", statsJson(r.hoe_move_s, ms)},
        {"oled_motion", statsJson(r.oled_move_s, ms)}}},
      {"stages", {{"hoe", r.hoe_stage}, {"foveal_display", r.oled_stage}}},
      {"frames", {{"captured", r.frames}, {"tracked", r.frames_found}}},
      {"calibration", {{"accuracy_deg", r.calibration_accuracy_deg}, {"precision_deg", r.calibration_precision_deg}}},
      {"duration_s", r.duration_s},
      {"inset_error_deg", statsJson(r.inset_error_deg)},
      {"off_fovea", {{"time_s", r.time_off_fovea_s}, {"fraction", r.time_off_fovea_s / d}}},
      {"beyond_tolerance", {{"time_s", r.time_beyond_tolerance_s}, {"fraction", r.time_beyond_tolerance_s / d}}},
      {"settle_ms", statsJson(r.settle_s, ms)},
      {"unsettled_saccades", r.unsettled},
      {"hoe_error_mm", statsJson(r.hoe_error_mm)},
      {"fov_loss",
       {{"partly_lost_s", r.fov_partly_lost_s},
        {"lost_s", r.fov_lost_s},
        {"partly_lost_fraction", r.fov_partly_lost_s / d},
        {"lost_fraction", r.fov_lost_s / d},
        {"mean_light_lost", r.mean_light_lost}}},
      {"saccade_stats",
       {{"count", r.saccades.size()},
        {"amplitude_deg", statsJson(devices::statsOf(amp))},
        {"peak_velocity_deg_s", statsJson(devices::statsOf(vel))},
        {"duration_ms", statsJson(devices::statsOf(dur), ms)}}}};
}

// --fixations FILE|N: a whole number is a count, anything else a file.
std::vector<devices::BinocularFixation> fixationsFrom(const std::string& text, unsigned seed) {
  const bool count = !text.empty() && text.size() <= 4 && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
  });
  if (count) {
    const int n = std::stoi(text);
    if (n < 1 || n > 200) usageError("--fixations: the count must be in [1, 200]");
    return devices::randomFixations(n, seed * 2654435761u + 17u);
  }
  std::vector<devices::BinocularFixation> out;
  try {
    const nlohmann::json doc = readJsonFile(text);
    const JsonFields top(doc, text);
    for (const JsonFields& f : top.objects("fixations", true, 200)) {
      devices::BinocularFixation b;
      b.distance_mm = 10 * f.number("distance_cm", Range::closed(20, 1000));
      const nlohmann::json* dir = f.get("direction_deg", false);
      if (dir != nullptr && dir->is_array()) {
        const auto v = f.numbers("direction_deg", Range::closed(-20, 20), 2);
        b.direction_deg = {v[0], v[1]};
      } else if (dir != nullptr) {
        b.direction_deg = {f.number("direction_deg", Range::closed(-20, 20)), 0};
      }
      b.hold_s = f.number("hold_ms", Range::closed(100, 10000), 1000.0) / 1000;
      out.push_back(b);
    }
    if (out.empty()) top.fail("fixations", "must hold at least one fixation");
    top.known({"notes"});
    top.rejectUnknownKeys();
  } catch (const std::exception& e) {
    inputError(std::string("closed-loop: ") + e.what());
  }
  return out;
}

nlohmann::json optionalMs(const std::optional<double>& s) {
  return s ? nlohmann::json(*s * 1000) : nlohmann::json(nullptr);
}

// One eye's focus stage: the keys of the top-level "focus_stage" (the right eye's).
nlohmann::json focusStageJson(const devices::FocusEye& f) {
  return {{"mirror_distance_mm", f.model.mirror_distance_mm},
          {"focal_length_mm", f.model.focal_length_mm},
          {"nominal_panel_mm", f.model.nominal_panel_mm},
          {"near_mm", f.travel.near_mm},
          {"far_mm", f.travel.far_mm},
          {"panel_near_mm", f.travel.panel_near_mm},
          {"panel_far_mm", f.travel.panel_far_mm},
          {"travel_mm", f.travel.travel_mm},
          {"range_d", f.travel.range_d},
          {"d_per_mm", {{"near", f.travel.sensitivity_near_d_per_mm}, {"far", f.travel.sensitivity_far_d_per_mm}}},
          {"resolution_d_per_count",
           {{"near", f.travel.sensitivity_near_d_per_mm / f.counts_per_mm},
            {"far", f.travel.sensitivity_far_d_per_mm / f.counts_per_mm}}}};
}

// One eye's block of "eyes".
nlohmann::json eyeJson(const devices::ClosedLoopResult& e, const devices::FocusEye& f) {
  const double ms = 1000;
  return {
      {"inset_error_deg", statsJson(e.inset_error_deg)},
      {"off_fovea_fraction", e.time_off_fovea_s / std::max(e.duration_s, 1e-12)},
      {"calibration", {{"accuracy_deg", e.calibration_accuracy_deg}, {"precision_deg", e.calibration_precision_deg}}},
      {"frames", {{"captured", e.frames}, {"tracked", e.frames_found}}},
      {"stages", {{"hoe", e.hoe_stage}, {"foveal_display", e.oled_stage}, {"focus", f.stage}}},
      {"focus_stage", focusStageJson(f)},
      {"focus_motion", statsJson(f.move_s, ms)}};
}

nlohmann::json binocularJson(const devices::BinocularResult& r, const devices::BinocularOptions& o) {
  const double ms = 1000;
  nlohmann::json fix = nlohmann::json::array();
  std::vector<double> times;
  int within = 0;
  for (const auto& f : r.fixations) {
    // Unsettled fixations count as never (infinite) in the median.
    times.push_back(f.time_to_tolerance_s ? *f.time_to_tolerance_s * ms : std::numeric_limits<double>::infinity());
    if (f.time_to_tolerance_s && *f.time_to_tolerance_s <= 0.3 &&
        std::abs(f.final_focus_error_worst_d) <= o.tolerance_d)
      ++within;
    fix.push_back(
        {{"distance_cm", f.fixation.distance_mm / 10},
         {"direction_deg", {f.fixation.direction_deg[0], f.fixation.direction_deg[1]}},
         {"hold_ms", f.fixation.hold_s * ms},
         {"onset_ms", f.onset_s * ms},
         {"vergence_change_deg", f.vergence_change_deg},
         {"time_to_0_25d_ms", optionalMs(f.time_to_tolerance_s)},
         {"eye_time_to_0_25d_ms", optionalMs(f.eye_time_to_tolerance_s)},
         {"final_focus_error_d", f.final_focus_error_worst_d},
         {"final_focus_error_per_eye_d", {{"left", f.final_focus_error_d[0]}, {"right", f.final_focus_error_d[1]}}},
         {"peak_focus_error_d", f.peak_focus_error_d},
         {"focus_motion_ms", f.focus_motion_s * ms},
         {"inset_on_fovea_fraction",
          {{"left", f.inset_on_fovea_fraction[0]}, {"right", f.inset_on_fovea_fraction[1]}}}});
  }
  std::vector<double> sorted = times;
  std::sort(sorted.begin(), sorted.end());
  nlohmann::json median = nullptr;
  if (!sorted.empty()) {
    const std::size_t n = sorted.size();
    const double m = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    if (std::isfinite(m)) median = m;
  }
  // Extremes over the fixations (docs/gaze-tracking.md's binocular table prints them); a time is
  // null when a fixation never got there.
  auto extreme = [&](auto value, bool want_max) -> nlohmann::json {
    if (r.fixations.empty()) return nullptr;
    double best = want_max ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
    for (const auto& f : r.fixations) {
      const std::optional<double> v = value(f);
      if (!v) return nullptr;
      best = want_max ? std::max(best, *v) : std::min(best, *v);
    }
    return best;
  };
  auto timeMs = [&](const std::optional<double>& s) { return s ? std::optional<double>(*s * ms) : std::nullopt; };
  const nlohmann::json time_max = extreme([&](const auto& f) { return timeMs(f.time_to_tolerance_s); }, true);
  const nlohmann::json eye_time_max = extreme([&](const auto& f) { return timeMs(f.eye_time_to_tolerance_s); }, true);
  const nlohmann::json peak_min =
      extreme([](const auto& f) { return std::optional<double>(f.peak_focus_error_d); }, false);
  const nlohmann::json peak_max =
      extreme([](const auto& f) { return std::optional<double>(f.peak_focus_error_d); }, true);
  const nlohmann::json final_max =
      extreme([](const auto& f) { return std::optional<double>(std::abs(f.final_focus_error_worst_d)); }, true);
  const nlohmann::json inset_left =
      extreme([](const auto& f) { return std::optional<double>(f.inset_on_fovea_fraction[0]); }, false);
  const nlohmann::json inset_right =
      extreme([](const auto& f) { return std::optional<double>(f.inset_on_fovea_fraction[1]); }, false);
  const auto& L = r.eyes[0];
  const auto& R = r.eyes[1];
  const double to_focus = r.to_command_s + r.vergence_s;
  auto path = [&](double to_cmd, const devices::Stats& s) {
    return s.count ? nlohmann::json(to_cmd * ms + s.mean * ms) : nlohmann::json(nullptr);
  };
  nlohmann::json out = {
      {"fixations", fix},
      {"summary",
       {{"fixations", r.fixations.size()},
        {"within_0_25d_fraction", r.fixations.empty() ? 0.0 : double(within) / double(r.fixations.size())},
        {"median_time_to_0_25d_ms", median},
        {"settled_fixations", std::count_if(times.begin(), times.end(), [](double x) { return std::isfinite(x); })},
        {"target_ms", 300},
        {"tolerance_d", o.tolerance_d},
        {"max_time_to_0_25d_ms", time_max},
        {"max_eye_time_to_0_25d_ms", eye_time_max},
        {"peak_focus_error_d", {{"min", peak_min}, {"max", peak_max}}},
        {"max_final_focus_error_d", final_max},
        {"min_inset_on_fovea_fraction", {{"left", inset_left}, {"right", inset_right}}}}},
      {"latency_budget_ms",
       {{"capture", R.capture_s * ms},
        {"detect", R.detect_s * ms},
        {"detect_measured_mean", 0.5 * (L.detect_measured_mean_s + R.detect_measured_mean_s) * ms},
        {"map", R.map_s * ms},
        {"command", R.command_s * ms},
        {"to_command", r.to_command_s * ms},
        {"vergence", r.vergence_s * ms},
        {"focus_to_command", to_focus * ms},
        {"hoe_motion", {{"left", statsJson(r.hoe_move_s[0], ms)}, {"right", statsJson(r.hoe_move_s[1], ms)}}},
        {"oled_motion", {{"left", statsJson(r.oled_move_s[0], ms)}, {"right", statsJson(r.oled_move_s[1], ms)}}},
        {"focus_motion", statsJson(r.focus_move_s, ms)},
        {"eye_vergence_latency", o.dynamics.latency_s * ms},
        {"paths",
         {{"periphery_hoe",
           {{"left", path(r.to_command_s, r.hoe_move_s[0])}, {"right", path(r.to_command_s, r.hoe_move_s[1])}}},
          {"inset_oled",
           {{"left", path(r.to_command_s, r.oled_move_s[0])}, {"right", path(r.to_command_s, r.oled_move_s[1])}}},
          {"focus", path(to_focus, r.focus_move_s)}}}}},
      {"stages", {{"hoe", R.hoe_stage}, {"foveal_display", R.oled_stage}, {"focus", r.focus_stage}}},
      {"focus_stage", focusStageJson(r.focus_eyes[1])},
      {"vergence",
       {{"ipd_mm", o.geometry.ipd_mm},
        {"samples", r.vergence_samples},
        {"invalid", r.vergence_invalid},
        {"tracker_sigma_deg", {{"left", r.precision_sd_deg_left}, {"right", r.precision_sd_deg_right}}},
        {"closed_form_sigma_d", r.closed_form_sigma_d_mean},
        {"measured_sigma_d_raw", r.measured_sigma_d_raw},
        {"measured_bias_d_raw", r.measured_bias_d_raw},
        {"measured_sigma_d_filtered", r.measured_sigma_d_filtered},
        {"dynamics",
         {{"latency_ms", o.dynamics.latency_s * ms},
          {"tau_ms", o.dynamics.tau_s * ms},
          {"peak_convergence_deg_s", o.dynamics.peak_convergence_deg_s},
          {"peak_divergence_deg_s", o.dynamics.peak_divergence_deg_s}}}}},
      {"eyes", {{"left", eyeJson(L, r.focus_eyes[0])}, {"right", eyeJson(R, r.focus_eyes[1])}}},
      {"duration_s", r.duration_s}};
  return out;
}

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("closed-loop", "Simulate the gaze-following loop on the virtual bench");
  struct Args {
    std::string scene, stage_model, sweep, fixations, focus_stage_model;
    bool binocular = false;
    double ipd_mm = 63;
    int saccades = 10;
    unsigned seed = 1;
    double fps = 120;
    bool json = false;
    std::string detector = "classical";
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("SCENE", a->scene, "scene file")->required();
  cmd->add_option("--saccades", a->saccades, "number of saccades (default 10)")->check(CLI::Range(1, 1000));
  addSeedOption(cmd, a->seed, "seed of the saccades and frames (default 1)");
  cmd->add_option("--stage-model", a->stage_model, "stage model of every axis (default: the scene's)")
      ->check(CLI::IsMember({"MTS25-Z8", "Z825B", "DDSM50"}));
  cmd->add_option("--fps", a->fps, "eye-camera frame rate (default 120)")->check(CLI::Range(1.0, 2000.0));
  cmd->add_option("--latency-sweep", a->sweep, "extra latencies (ms), comma-separated, e.g. 0,10,20,50");
  cmd->add_flag("--json", a->json, "print the result as JSON");
  cmd->add_option("--detector", a->detector,
                  "pupil detector of the calibration and the loop: classical (default), learned or auto");
  cmd->add_flag("--binocular", a->binocular, "both eyes (each on its own train), vergence and focus stages");
  cmd->add_option("--fixations", a->fixations, "with --binocular: a fixation file (JSON) or a count of random ones");
  CLI::Option* ipd_option =
      cmd->add_option(
             "--ipd", a->ipd_mm,
             "with --binocular: interpupillary distance in mm (default: the scene's binocular.ipd_mm, else 63)")
          ->check(CLI::Range(40.0, 80.0));
  cmd->add_option("--focus-stage-model", a->focus_stage_model,
                  "with --binocular: the focus stages' model (default: the micro-OLED's)")
      ->check(CLI::IsMember({"MTS25-Z8", "Z825B", "DDSM50"}));
  cmd->callback([a, ipd_option] {
    const gaze::PupilDetectorKind kind = detectorOrExit(a->detector);
    if (!a->binocular && (!a->fixations.empty() || !a->focus_stage_model.empty()))
      usageError("closed-loop: --fixations and --focus-stage-model need --binocular");
    if (a->binocular && a->fixations.empty()) usageError("closed-loop: --binocular needs --fixations FILE|N");
    if (a->binocular && !a->sweep.empty()) usageError("closed-loop: --latency-sweep is not available with --binocular");
    const Scene scene = loadSceneOrExit(a->scene);
    if (a->binocular) {
      devices::BinocularOptions bo;
      bo.loop.camera_fps = a->fps;
      bo.loop.detector = kind;  // both eye trackers (and their calibrations)
      if (bo.loop.exposure_s + bo.loop.readout_s > 1.0 / bo.loop.camera_fps)
        bo.loop.exposure_s = 0.5 / bo.loop.camera_fps, bo.loop.readout_s = 0.4 / bo.loop.camera_fps;
      if (!a->stage_model.empty()) bo.loop.stage_model = a->stage_model;
      if (!a->focus_stage_model.empty()) bo.focus_stage_model = a->focus_stage_model;
      // The IPD: --ipd, else a binocular scene's (its "binocular" block), else 63 mm.
      const bool ipd_given = ipd_option->count() > 0;
      bo.geometry.ipd_mm = ipd_given || !scene.binocular ? a->ipd_mm : scene.binocular->ipd_mm;
      const char* ipd_source = ipd_given ? "--ipd" : scene.binocular ? "scene" : "default";
      // The eye cameras' seeds as `calibrate gaze` and the capture wizard's (the same calibrations).
      bo.seed_right = gaze::eyeCameraSeed(EyeSide::Right, a->seed);
      bo.seed_left = gaze::eyeCameraSeed(EyeSide::Left, a->seed);
      const auto fixations = fixationsFrom(a->fixations, a->seed);
      devices::BinocularResult br;
      try {
        // Each eye on its own train: a binocular scene's eyeScene(scene, EyeSide::Left|Right), a
        // monocular scene as the right eye with its mirror image as the left.
        br = devices::runBinocularLoop(scene, fixations, bo);
      } catch (const std::invalid_argument& e) {
        inputError(std::string("closed-loop: ") + e.what());
      }
      nlohmann::json out = binocularJson(br, bo);
      out["vergence"]["ipd_source"] = ipd_source;
      out["scene"] = scene.name;
      out["seed"] = a->seed;
      out["binocular"] = true;
      out["detector"] = gaze::detectorName(kind);
      out["camera"] = {{"fps", bo.loop.camera_fps}, {"exposure_ms", bo.loop.exposure_s * 1000}};
      if (a->json) {
        printJson(out);
        return;
      }
      std::cout << "binocular closed loop, " << br.fixations.size() << " fixations, focus stage " << br.focus_stage
                << ": within 0.25 D in 300 ms for " << out["summary"]["within_0_25d_fraction"].get<double>() * 100
                << " % of the fixations, median time to 0.25 D " << out["summary"]["median_time_to_0_25d_ms"].dump()
                << " ms\n";
      return;
    }
    devices::ClosedLoopOptions o;
    o.saccades = a->saccades;
    o.seed = a->seed;
    o.camera_fps = a->fps;
    o.detector = kind;
    if (o.exposure_s + o.readout_s > 1.0 / o.camera_fps)
      o.exposure_s = 0.5 / o.camera_fps, o.readout_s = 0.4 / o.camera_fps;
    if (!a->stage_model.empty()) o.stage_model = a->stage_model;
    std::vector<double> sweep;
    if (!a->sweep.empty()) {
      sweep = parseNumberList(a->sweep, "--latency-sweep", 1, 20);
      for (double s : sweep)
        if (!(s >= 0 && s <= 1000)) usageError("--latency-sweep: latencies must be in [0, 1000] ms");
    }
    devices::TrackedRun run;
    try {
      run = devices::trackTrajectory(scene, o);
    } catch (const std::invalid_argument& e) {
      inputError(std::string("closed-loop: ") + e.what());
    }
    const devices::ClosedLoopResult r = devices::simulateStages(scene, run, o);
    nlohmann::json out = resultJson(r);
    out["scene"] = scene.name;
    out["saccades"] = a->saccades;
    out["detector"] = gaze::detectorName(kind);
    out["seed"] = a->seed;
    out["camera"] = {{"fps", o.camera_fps}, {"exposure_ms", o.exposure_s * 1000}};
    nlohmann::json rows = nlohmann::json::array();
    for (double ms : sweep) {
      devices::ClosedLoopOptions os = o;
      os.extra_latency_s = ms / 1000;
      const devices::ClosedLoopResult s = devices::simulateStages(scene, run, os);
      const double d = std::max(s.duration_s, 1e-12);
      rows.push_back(
          {{"extra_latency_ms", ms},
           {"to_command_ms", s.latency_to_command_s * 1000},
           {"inset_error_deg_mean", s.inset_error_deg.mean},
           {"inset_error_deg_max", s.inset_error_deg.max},
           {"off_fovea_fraction", s.time_off_fovea_s / d},
           {"settle_ms_mean", s.settle_s.count ? nlohmann::json(s.settle_s.mean * 1000) : nlohmann::json(nullptr)},
           {"unsettled_saccades", s.unsettled},
           {"fov_partly_lost_fraction", s.fov_partly_lost_s / d},
           {"fov_lost_fraction", s.fov_lost_s / d}});
    }
    out["latency_sweep"] = rows;
    if (a->json) {
      printJson(out);
      return;
    }
    std::cout << "closed loop, " << r.saccades.size() << " saccades on " << r.hoe_stage << "/" << r.oled_stage << ": "
              << r.latency_to_command_s * 1000 << " ms to command, inset error mean " << r.inset_error_deg.mean
              << " deg (max " << r.inset_error_deg.max << "), off the fovea " << r.time_off_fovea_s << " s of "
              << r.duration_s << " s, FOV lost " << r.fov_lost_s << " s\n";
  });
}

const Registrar reg{"closed-loop", &install};

}  // namespace
}  // namespace cmd_closed_loop
}  // namespace fovea::cli
