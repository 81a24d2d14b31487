#pragma once
// A tolerance specification (docs/tolerancing.md): what a built unit varies, how it is drawn,
// what is computed per trial and what passes.
//
// Parameters (each one scalar input x of a trial, drawn from its distribution):
//   kind "scene"              : an offset added to a number of the scene file at `path`
//                               (element positions and tilts, layer thickness, n1, shrinkage,
//                               pupil diameter, eye relief...: every path withParameter() takes)
//   kind "laser_temperature"  : a temperature change dT (K) of the lasers; every projector
//                               wavelength moves by drift_nm_per_K x dT (seed B.2.2: laser
//                               wavelength drift with temperature; one value or one per laser)
//   kind "stage_repeatability": an offset (mm) of every position the HOE/source stage reaches
//   kind "stage_backlash"     : lost motion b (mm): a move ends b/2 short of its target, on the
//                               side it came from
//   kind "gaze_tracker"       : an error (deg) of the gaze the tracker reports along the axis
// Distributions: "normal" (sigma), "uniform" (half_width), "truncated_normal" (sigma, limit:
// |x - mean| <= limit); each with an optional "mean" (default 0).
//
// Sampling is counter-based: the draw of parameter p in trial i is a pure function of
// (seed, i, p), so any slice of the trials can run anywhere (shards) with the same values.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/analysis/gaze_studies.h"

namespace fovea {

enum class ToleranceKind { Scene, LaserTemperature, StageRepeatability, StageBacklash, GazeTracker };
enum class Distribution { Normal, Uniform, TruncatedNormal };

struct ToleranceParameter {
  std::string name;  // as reported (default: the path or the kind)
  ToleranceKind kind = ToleranceKind::Scene;
  std::string path;  // Scene
  Distribution distribution = Distribution::Normal;
  double mean = 0, sigma = 0, half_width = 0, limit = 0;
  std::vector<double> drift_nm_per_K;  // LaserTemperature: one value, or one per projector wavelength

  // The value at probability u in (0, 1) (inverse CDF).
  double quantile(double u) const;
  // Density ratio p_c(x) / p(x) of the distribution scaled about its mean by c (widths x c)
  // against the spec one; 0 outside the scaled support.
  double scaledDensityRatio(double x, double c) const;
  double width() const;  // sigma or half_width: the number the inverse scales
  bool bounded() const { return distribution != Distribution::Normal; }
};

enum class Compensator { Refind, Fixed };

struct FigureBound {
  std::optional<double> min, max;
};

// NOLINTNEXTLINE(bugprone-exception-escape): the implicit members copy json/vectors; std::bad_alloc only.
struct ToleranceSpec {
  std::vector<ToleranceParameter> parameters;
  GazeAxis axis = GazeAxis::Yaw;
  ShiftMethod method = ShiftMethod::Hoe;
  Compensator compensator = Compensator::Refind;
  std::vector<double> gazes_deg;      // the gaze samples of every trial (from/to/step)
  double eyebox_tolerance_deg = 3.0;  // eye box: FOV >= FOV(0) - this
  // Figure name -> bounds; a trial passes when every bounded figure is inside.
  std::vector<std::pair<std::string, FigureBound>> pass;
  double target_yield = 0.9;
  bool sobol = true;                // Saltelli design (trials in blocks of parameters + 2) or plain Monte Carlo
  int bootstrap = 200;              // resamples for the index errors
  double fov_tolerance_deg = 0.02;  // edge tolerance of the FOV estimator
  std::optional<double> wavelength_nm;
  GazeStudyOptions optimiser;  // x_p search (bracket points, bisections)
  nlohmann::json source;       // the spec as read (echoed in the output)
};

// Limits of a spec: gazes within +-80 deg (the CLI's gaze limit), at most 64 parameters.
inline constexpr double kToleranceGazeLimitDeg = 80.0;
inline constexpr std::size_t kMaxToleranceParameters = 64;

// Every field typed and range-checked through model/io/json_fields.h; throws
// std::invalid_argument "SOURCE: json.path: problem" naming the first offending key.
ToleranceSpec parseToleranceSpec(const nlohmann::json& j, const std::string& source = "tolerance spec");

// The spec against the scene it tolerances: every "scene" parameter's path must name a real
// number of the scene file (an integer field such as projector.pixels[0] cannot take an
// offset: every unit would be invalid). Throws std::invalid_argument
// "SOURCE: parameters[i].path: problem".
void checkToleranceSpecPaths(const ToleranceSpec& spec, const Scene& scene,
                             const std::string& source = "tolerance spec");

// Names of the per-trial figures, in output order.
const std::vector<std::string>& toleranceFigureNames();

// Counter-based uniform draw in (0, 1): trial i, stream s (0: A matrix, 1: B matrix), parameter p.
double counterUniform(std::uint64_t seed, std::uint64_t trial, std::uint64_t stream, std::uint64_t parameter);

// The inputs of trial i: with the Saltelli design, block j = i / (k + 2) and role r = i % (k + 2):
// r 0 -> row j of A, 1 -> row j of B, 2 + p -> A with column p taken from B (A_B^(p)).
std::vector<double> trialInputs(const ToleranceSpec& spec, std::uint64_t seed, std::uint64_t trial);

}  // namespace fovea
