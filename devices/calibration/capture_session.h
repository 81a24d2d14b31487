#pragma once
// Running a capture plan on a bench and keeping everything it captured in a folder.
//
// The folder holds manifest.json ("fovea-capture-session", version 1: the plan, one record
// per capture, imported measurement files) and one 8-bit PNG per capture. The manifest is
// rewritten (write to a temporary file, then rename) after every capture, so a session that
// is paused, closed or killed loses nothing it captured; opening the folder again with the
// same plan resumes at the first step not captured yet.
//
// A step: the other display is switched off and the step's pattern shown, every stage
// target is sent to its axis worker (all axes move at once), and the camera frame is the
// first one exposed after the last axis settled (captureSettled(): no stale frame).
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "devices/calibration/capture_plan.h"
#include "devices/camera/camera.h"

namespace fovea::devices {

class Bench;

// What a session needs of the bench: the stages, a camera on the stages' clock, and the
// displays (the virtual bench: VirtualOptics::show).
struct BenchRig {
  Bench* bench = nullptr;
  Camera* camera = nullptr;
  std::function<void(BenchDisplay, const image::DisplayPattern&)> show;
  std::function<BenchPose(double)> pose;  // optional: the pose at a camera time (virtual bench)
  bool is_virtual = false;
};

struct CaptureRecord {
  std::string step;   // CaptureStep::id
  std::string image;  // file name in the session folder
  std::uint64_t sequence = 0;
  double exposure_start_s = 0, exposure_s = 0;
  int discarded_frames = 0;                 // stale frames thrown away after the move
  std::map<std::string, double> positions;  // "hoe.x" -> element coordinate at capture
  std::optional<BenchPose> pose;            // virtual bench: the pose the frame was rendered at
};

class CaptureSession {
 public:
  // `folder` empty: nothing is written (the CLI without --output keeps frames in memory).
  // An existing manifest in `folder` with the same kind and step ids is resumed; one with a
  // different plan is an error (std::runtime_error) rather than mixed with this one.
  CaptureSession(CaptureKind kind, std::vector<CaptureStep> plan, std::filesystem::path folder,
                 std::string scene_name = {});

  CaptureKind kind() const { return kind_; }
  const std::vector<CaptureStep>& plan() const { return plan_; }
  const std::filesystem::path& folder() const { return folder_; }
  bool done(std::size_t step) const;
  std::optional<std::size_t> nextStep() const;  // first step not captured
  std::size_t capturedCount() const { return records_.size(); }
  bool complete() const { return !nextStep().has_value(); }
  const std::vector<CaptureRecord>& records() const { return records_; }
  const CaptureRecord* record(const std::string& step_id) const;
  // The frame of a capture: kept in memory for this run, else read back from the folder.
  cv::Mat image(const std::string& step_id) const;

  // Runs one step on the rig (blocking: moves, settle, capture), stores and saves it.
  // Throws DeviceError on a device problem (the step stays uncaptured).
  const CaptureRecord& capture(std::size_t step, BenchRig& rig);

  // Copies a measurement file (colour: "fovea-color-measurements" JSON, checked by the
  // model's parser) into the folder and lists it in the manifest. Throws
  // std::invalid_argument when it does not parse.
  std::filesystem::path importMeasurement(const std::filesystem::path& file);
  const std::vector<std::string>& measurements() const { return measurements_; }

  // The gaze session's result (the pupil-tracked 5-point calibration and its accuracy and
  // precision on the held-out grid): kept in the manifest under "gaze_calibration", saved at once.
  // A binocular scene's session also keeps its left eye camera's under "gaze_calibration_left"
  // ("gaze_calibration" is then the right eye's); null `left` removes it.
  void setGazeCalibration(nlohmann::json result, nlohmann::json left = nullptr);
  const nlohmann::json& gazeCalibration() const { return gaze_calibration_; }           // null when none
  const nlohmann::json& leftGazeCalibration() const { return left_gaze_calibration_; }  // null when none

  nlohmann::json manifest() const;
  void save() const;

 private:
  CaptureKind kind_;
  std::vector<CaptureStep> plan_;
  std::filesystem::path folder_;
  std::string scene_name_;
  std::vector<CaptureRecord> records_;
  std::map<std::string, cv::Mat> frames_;
  std::vector<std::string> measurements_;
  nlohmann::json gaze_calibration_, left_gaze_calibration_;
};

}  // namespace fovea::devices
