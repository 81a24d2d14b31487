// fovea-cli calibrate geometric --virtual [--scene SCENE] [--json] [--output DIR]
//                               [--gazes LIST] [--model poly2|poly3] [--hoe-shift optimal|geometric]
//                               [--noise DN] [--seed N]
// Geometric calibration (seed B.2.1) on the virtual bench: the checkerboard sequence of the
// geometric capture plan (devices/calibration/capture_plan.h: per gaze, the HOE at x_p and
// the micro-OLED at x_f, a board on each display) is captured through the emulated stages
// (every move goes through the APT emulator; each frame is the first exposed after the last
// axis settled), the corners are detected, a warp display px -> camera px is fitted per
// capture, and the warps are compared with the virtual bench's ground truth.
// --json prints {"captures": N, "residual_px_rms": R, "ground_truth_error_px": E}:
// captures taken, RMS corner residual of the fits over all captures, RMS distance between
// the fitted warps and the true display -> camera maps over the boards (camera pixels).
// --output DIR keeps the session (manifest.json, one PNG per capture) and calibration.json
// (per-capture fits and warp coefficients). Exit 1 when a board is not found.
//
// fovea-cli calibrate gaze --virtual [--scene SCENE] [--eye left|right|both]
//                          [--detector classical|learned|auto] [--seed N] [--json]
// The gaze calibration of the capture wizard's gaze session (seed C.4) on the virtual eye
// cameras: the pupil tracker on rendered IR frames of the 5 calibration targets, accuracy and
// precision on the 8 held-out ones (model/gaze/tracked_calibration.h). Every eye camera of
// the scene (model/gaze/eye_tracker_calibration.h): a binocular scene's two unless --eye
// picks one, with the seeds of `closed-loop --binocular --seed N` (the same calibrations).
// --json: the manifest's "gaze_calibration" document (accuracy_mean_deg, precision_rms_s2s_deg,
// ...); for both eyes the right eye's plus "eyes": {"left", "right"} (app/cli/eye_option.h).
// Exit 1 when a target keeps too few confident detections.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "app/cli/analysis_options.h"
#include "app/cli/cli_common.h"
#include "app/cli/detector_option.h"
#include "app/cli/eye_option.h"
#include "devices/bench/live_bench.h"
#include "devices/transport/device_error.h"
#include "model/gaze/eye_tracker_calibration.h"
#include "model/image/geometric_calibration.h"
#include "model/io/output_file.h"

namespace fovea::cli {
namespace cmd_calibrate {  // one per command file: fovea-cli compiles in unity batches
namespace {

using devices::DeviceError;

struct Args {
  bool is_virtual = false, json = false;
  std::string scene, output, gazes, model = "poly3", hoe_shift = "optimal";
  double noise = 2.0;
  unsigned seed = 1;
};

void run(const Args& a) {
  if (!a.is_virtual) usageError("calibrate geometric needs --virtual (hardware display output is not available)");
  const Scene scene = loadSceneOrExit(a.scene);
  devices::GeometricPlanOptions po;
  if (!a.gazes.empty()) po.gazes_yaw_deg = parseNumberList(a.gazes, "--gazes", 1, 64);
  if (a.hoe_shift == "optimal") po.hoe_shift = devices::analysedHoeShift(scene);
  const devices::Plan plan = devices::geometricPlan(scene, po);
  for (const auto& s : plan.skipped) std::cerr << "skipped: " << s << "\n";
  if (plan.steps.empty()) inputError("the geometric plan has no capture within the stages' soft limits");
  const image::WarpModel model = *image::warpModelFromString(a.model);

  devices::LiveBenchOptions lo;
  lo.allow_hardware = false;
  lo.clock = std::make_shared<devices::SimulatedClock>();  // moves and settling take no wall time
  lo.camera_seed = a.seed;
  lo.camera_noise_dn = a.noise;
  devices::LiveBench live(scene, lo);
  for (auto& f : live.bench().connectAll()) f.get();
  devices::VirtualOptics& optics = *live.optics();
  live.camera().open();
  devices::CaptureSession session(devices::CaptureKind::Geometric, plan.steps, a.output, scene.name);
  devices::BenchRig rig = live.rig();

  Progress progress("calibrate");
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    if (session.done(i)) continue;
    session.capture(i, rig);
    progress.update(0.7 * (i + 1) / plan.steps.size());
  }

  image::ErrorTally residual, truth;
  nlohmann::json per_capture = nlohmann::json::array();
  std::vector<std::string> missing;
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    const devices::CaptureStep& step = plan.steps[i];
    const devices::CaptureRecord* rec = session.record(step.id);
    if (!rec) continue;
    const auto obs = image::observeBoard(session.image(step.id), step.pattern);
    if (!obs) {
      missing.push_back(step.id);
      continue;
    }
    const image::DisplayWarpFit fit = image::fitDisplayWarp(*obs, model);
    image::ErrorTally r;
    for (const auto& p : obs->pairs) {
      r.sum_sq += (fit.warp.apply(p.src) - p.dst).squaredNorm();
      ++r.count;
    }
    residual.add(r);
    const auto gt = optics.groundTruth(step.display, rec->pose.value_or(optics.poseAt(rec->exposure_start_s)));
    const image::ErrorTally e =
        image::compareWithTruth(fit.warp, step.pattern, [&gt](const Eigen::Vector2d& p) { return gt->toCamera(p); });
    truth.add(e);
    per_capture.push_back({{"step", step.id},
                           {"image", rec->image},
                           {"display", toString(step.display)},
                           {"gaze_deg", step.gaze_deg},
                           {"corners", fit.corners},
                           {"orientation", obs->orientation},
                           {"residual_px_rms", fit.residual_px_rms},
                           {"ground_truth_error_px", e.rms()},
                           {"model", a.model},
                           {"warp", fit.warp.coefficients()}});
    progress.update(0.7 + 0.3 * (i + 1) / plan.steps.size());
  }
  if (!a.output.empty()) {
    nlohmann::json report{{"format", "fovea-geometric-calibration"},
                          {"version", 1},
                          {"scene", scene.name},
                          {"captures", session.capturedCount()},
                          {"residual_px_rms", residual.rms()},
                          {"ground_truth_error_px", truth.rms()},
                          {"skipped", plan.skipped},
                          {"boards_not_found", missing},
                          {"per_capture", per_capture}};
    try {
      writeOutputFile(std::filesystem::path(a.output) / "calibration.json", report.dump(2) + "\n");
    } catch (const OutputError& e) {
      inputError(e.what());
    }
  }
  if (!missing.empty()) {
    std::string list;
    for (const auto& m : missing) list += (list.empty() ? "" : ", ") + m;
    inputError("checkerboard not found in " + std::to_string(missing.size()) + " capture(s): " + list);
  }
  if (a.json) {
    printJson({{"captures", session.capturedCount()},
               {"residual_px_rms", residual.rms()},
               {"ground_truth_error_px", truth.rms()}});
    return;
  }
  std::cout << session.capturedCount() << " captures; corner residual " << residual.rms()
            << " px RMS; error against the ground truth " << truth.rms() << " px RMS\n";
  for (const auto& c : per_capture)
    std::cout << "  " << c["step"].get<std::string>() << ": residual " << c["residual_px_rms"].get<double>()
              << " px, ground truth " << c["ground_truth_error_px"].get<double>() << " px\n";
}

struct GazeArgs {
  bool is_virtual = false, json = false;
  std::string scene, detector = "classical";
  unsigned seed = 1;
};

void runGaze(const GazeArgs& a, const std::string& eye) {
  if (!a.is_virtual) usageError("calibrate gaze needs --virtual (no eye camera on USB is supported yet)");
  const gaze::PupilDetectorKind kind = detectorOrExit(a.detector);
  const Scene scene = loadSceneOrExit(a.scene);
  const std::vector<EyeRun> runs = eyeRuns(scene, eye, a.scene.empty() ? "the embedded scene" : a.scene);
  std::vector<nlohmann::json> docs;
  for (const EyeRun& run : runs) {
    const gaze::TrackedCalibrationOptions o = gaze::eyeTrackerCalibrationOptions(scene, run.side, kind, a.seed);
    try {
      docs.push_back(trackedCalibrationJson(gaze::calibrateWithTracker(o), o));
    } catch (const std::invalid_argument& e) {
      throw CliError(1, eyePrefix(run) + e.what());
    }
  }
  if (a.json) {
    std::cout << combineEyeDocuments(runs, docs).dump(2) << "\n";
    return;
  }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const nlohmann::json& d = docs[i];
    std::cout << eyePrefix(runs[i]) << "gaze calibration (" << d["detector"].get<std::string>() << "): accuracy "
              << d["accuracy_mean_deg"].get<double>() << " deg mean (max " << d["accuracy_max_deg"].get<double>()
              << "), precision " << d["precision_rms_s2s_deg"].get<double>() << " deg RMS sample-to-sample over "
              << d["held_out_targets"].get<int>() << " held-out targets; " << d["frames"].get<int>() << " frames, "
              << d["rejected"].get<int>() << " rejected\n";
  }
}

void installGaze(CLI::App* cmd) {
  auto* gz = cmd->add_subcommand("gaze", "Gaze calibration by the pupil tracker on the eye camera(s) (C.4)");
  auto a = std::make_shared<GazeArgs>();
  gz->add_flag("--virtual", a->is_virtual, "the virtual bench's eye camera(s) (rendered IR frames)");
  gz->add_option("--scene", a->scene, "scene file (default: the embedded prototype bench)");
  gz->add_flag("--json", a->json, "print the calibration document (the capture manifest's \"gaze_calibration\")");
  gz->add_option("--detector", a->detector, "pupil detector: classical (default), learned or auto");
  addSeedOption(gz, a->seed, "eye-camera noise seed (default 1; the left eye's is seed + 1000003)");
  auto eye = addEyeOption(gz);
  gz->callback([a, eye] { runGaze(*a, *eye); });
}

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("calibrate", "Calibration captures on the bench");
  cmd->require_subcommand(1);
  auto* geo = cmd->add_subcommand("geometric", "Geometric warps from checkerboard captures (B.2.1)");
  auto a = std::make_shared<Args>();
  geo->add_flag("--virtual", a->is_virtual, "run on the virtual bench (emulated stages, virtual eye camera)");
  geo->add_option("--scene", a->scene, "scene file (default: the embedded prototype bench)");
  geo->add_flag("--json", a->json, "print {\"captures\":N,\"residual_px_rms\":R,\"ground_truth_error_px\":E}");
  geo->add_option("--output", a->output, "folder for the session (manifest, PNG captures) and calibration.json");
  geo->add_option("--gazes", a->gazes, "gaze yaw angles in degrees, comma separated (default: 5 over the gaze range)");
  geo->add_option("--model", a->model, "warp model: poly2 or poly3 (default)")
      ->check(CLI::IsMember({"poly1", "poly2", "poly3", "homography"}));
  geo->add_option("--hoe-shift", a->hoe_shift, "x_p(alpha): optimal (analyses, default) or geometric")
      ->check(CLI::IsMember({"optimal", "geometric"}));
  addCheckedOption(geo, "--noise", a->noise,
                   analysis::number("noise", "Read noise", "DN", 2.0, 0.0, 50.0, 2, "camera read noise"));
  addSeedOption(geo, a->seed, "camera noise seed (default 1)");
  installGaze(cmd);
  geo->callback([a] {
    try {
      run(*a);
    } catch (const DeviceError& e) {
      throw CliError(e.kind() == DeviceError::Kind::Timeout || e.kind() == DeviceError::Kind::Disconnected ? 3 : 1,
                     e.what());
    } catch (const std::runtime_error& e) {
      if (dynamic_cast<const CliError*>(&e)) throw;
      throw CliError(1, e.what());
    }
  });
}

const Registrar reg{"calibrate", &install};

}  // namespace
}  // namespace cmd_calibrate
}  // namespace fovea::cli
