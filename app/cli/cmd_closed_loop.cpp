// fovea-cli closed-loop SCENE --saccades N --seed S [--stage-model M] [--fps F]
//                         [--latency-sweep MS,...] [--json]
// The closed gaze loop on the virtual bench (devices/bench/closed_gaze_loop.h): rendered
// eye-camera frames -> pupil detector -> C.4 calibration map -> HOE and micro-OLED stages
// following the gaze through a main-sequence saccade sequence. Reports the latency budget
// (capture, detect, map, command, stage motion), the foveal inset's error and the FOV lost
// while the HOE is in transit; --latency-sweep repeats the stage simulation with extra
// latency added before the command (the same tracked frames).
#include <iostream>

#include "app/cli/cli_common.h"
#include "devices/bench/closed_gaze_loop.h"

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

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("closed-loop", "Simulate the gaze-following loop on the virtual bench");
  struct Args {
    std::string scene, stage_model, sweep;
    int saccades = 10;
    unsigned seed = 1;
    double fps = 120;
    bool json = false;
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
  cmd->callback([a] {
    const Scene scene = loadSceneOrExit(a->scene);
    devices::ClosedLoopOptions o;
    o.saccades = a->saccades;
    o.seed = a->seed;
    o.camera_fps = a->fps;
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
