#pragma once
// The observables a fit target can name (docs/fitting.md): each is a number the existing
// analyses compute for a scene — the FOV at a gaze (trace_evaluator.h, fov_edges.h), the HOE
// travel x_p or the source travel z_s at a gaze and the eye box and gaze coverage of a method
// (gaze_studies.h), the mean efficiency, the angular resolution at an eccentricity
// (angular_resolution.h), the RMS pixel spot on the HOE (beam_shaping.h). No new physics.
//
// How to add an observable: one ObservableDefinition in observableTable() (fit_observables.cpp)
// with its name, unit, parameters (name, default, allowed values) and evaluate function; the
// targets parser, the fitter, the CLI and the studio take it from there.

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/analysis/gaze_studies.h"
#include "model/scene/scene.h"

namespace fovea {

// What the observables share while one scene is evaluated: the FOV evaluators (per laser
// selection) and the results several targets read (an x_p search, a gaze sweep), computed once.
struct ObservableSettings {
  double fov_tolerance_deg = 1e-4;  // edge FOV estimator: each edge to this (smooth enough for differences)
  int shift_bisections = 12;        // x_p plateau edges bisected this often (GazeStudyOptions::edge_bisections)
  int border_bisections = 10;       // eye-box borders (GazeStudyOptions::border_bisections)
};

class ObservableContext {
 public:
  ObservableContext(const Scene& scene, const ObservableSettings& settings) : scene_(scene), settings_(settings) {}
  const Scene& scene() const { return scene_; }
  const ObservableSettings& settings() const { return settings_; }
  // The edge FOV evaluator of one laser (nothing: every projector laser).
  const FovEvaluator& evaluator(std::optional<double> wavelength_nm);
  // The x_p search of a gaze and the eye box of a gaze sweep, memoised by their inputs. The
  // eye box is sweepGaze's, walked lazily (eyebox_walk.h) over this memo: its zero gaze is the
  // x_p target's at gaze 0, and the sweep gazes past the borders are never searched.
  // Thread-safe: targets evaluate in parallel (evaluateTargets) and the eye box's two sides
  // search in parallel; each value is computed once, a concurrent caller of the same one waits.
  const GazeSample& optimalShift(double gaze_deg, GazeAxis axis, ShiftMethod method,
                                 std::optional<double> wavelength_nm, const GazeStudyOptions& options);
  const EyeBox& eyeBox(double from_deg, double to_deg, double step_deg, GazeAxis axis, ShiftMethod method,
                       std::optional<double> wavelength_nm, const GazeStudyOptions& options);

 private:
  template <class T>
  struct Once {
    std::once_flag flag;
    std::optional<T> value;
  };
  template <class T, class Compute>
  const T& once(std::map<std::string, std::unique_ptr<Once<T>>>& memo, const std::string& key, Compute&& compute);

  const Scene& scene_;
  ObservableSettings settings_;
  std::mutex mutex_;  // guards the maps (their nodes never move: references stay valid)
  std::map<std::string, FovEvaluator> evaluators_;
  std::map<std::string, std::unique_ptr<Once<GazeSample>>> shifts_;
  std::map<std::string, std::unique_ptr<Once<EyeBox>>> eyeboxes_;
};

struct ObservableParameter {
  std::string name;                  // key in the target object: "gaze_deg"
  nlohmann::json default_value;      // null: not set (its help says what that means)
  std::vector<std::string> choices;  // text values allowed (empty: a number, or a list of numbers)
  std::string help;
};

struct ObservableDefinition {
  std::string name;  // "fov_deg"
  std::string unit;  // the unit of value and sigma: "deg", "mm", "cpd", "um", ""
  std::string description;
  std::vector<ObservableParameter> parameters;
  // The model's value for validated parameters (every parameter present, defaults filled).
  // Throws std::runtime_error when the scene gives no value (no line of sight, no eye box).
  std::function<double(ObservableContext&, const nlohmann::json& parameters)> evaluate;
};

const std::vector<ObservableDefinition>& observableTable();
const ObservableDefinition* findObservable(const std::string& name);
std::string observableNames();  // "fov_deg, x_p_mm, ..." for messages

// Checks and completes one target's observable parameters against the definition: unknown
// keys, wrong types and values outside their choices are refused (std::invalid_argument,
// naming the key); defaults are filled in.
nlohmann::json completeObservableParameters(const ObservableDefinition& def, const nlohmann::json& given);

}  // namespace fovea
