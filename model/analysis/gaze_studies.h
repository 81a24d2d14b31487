#pragma once
// Gaze-dependent studies of the peripheral display (supplement A.3, A.4) and parameter
// sensitivity sweeps, built on a field-of-view evaluator (normally traceScene, see
// trace_evaluator.h; tests may pass a closed-form one).
//
// HOE travel x_p(alpha): for each gaze the lateral HOE shift (HOE local x for yaw, y for
// pitch) that maximises the retinal FOV along the swept axis. With a Maxwellian focus the
// FOV is a plateau in the shift: full while the focus stays inside the pupil (about a pupil
// diameter of travel), then a cliff when it leaves, or a slope where Bragg mismatch
// darkens the field. On the plateau the ray-sampled FOV only jitters by a ray spacing
// (1-3 deg), so its argmax is noise. x_p is therefore the middle of the plateau: a bracket
// of bracket_points shifts around the geometric guess (the pupil's lateral travel, r sin
// alpha) gives the best FOV F*; the plateau spans the shifts whose FOV is within
// plateau_tolerance_deg of F*, its two edges bisected (edge_bisections); x_p is their
// midpoint and the FOV reported is the one traced at x_p. (The seed's "shift giving the
// maximum FOV" in A.3; the midpoint is that maximum made well-defined and centres the
// Maxwellian focus on the pupil.)
// Eye box: the pupil-centre positions (bench mm along the axis) over the contiguous gaze
// range around zero gaze whose optimised FOV stays within tolerance_deg of the zero-gaze
// FOV; its borders are refined by bisection of the gaze angle.
// Source shift (A.4): the same, moving the projector point source along bench z instead.

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/analysis/study_runner.h"
#include "model/scene/scene.h"
#include "model/scene/scene_parameters.h"  // withParameter, parameterValue

namespace fovea {

enum class GazeAxis { Yaw, Pitch };
// None: nothing moves (the static eye box, the baseline both dynamic methods extend).
enum class ShiftMethod { Hoe, Source, None };

struct FovSample {
  double horizontal_deg = 0, vertical_deg = 0, diagonal_deg = 0;
  double extent_horizontal_deg = 0, extent_vertical_deg = 0;  // lit extent incl. holes (tracer's FOV)
  double mean_efficiency = 0;
  double efficiency_uniformity = 0;  // 1 - coefficient of variation of the efficiencies of rays reaching the pupil
  int rays_in_pupil = 0;
};

struct FovQuery {
  std::array<double, 2> gaze_deg{0, 0};
  std::array<double, 2> hoe_shift_mm{0, 0};
  double source_shift_mm = 0;
};

using FovEvaluator = std::function<FovSample(const Scene&, const FovQuery&)>;

struct GazeStudyOptions {
  double tolerance_deg = 3.0;          // eye-box criterion: FOV >= FOV(0) - tolerance (above the ~1-2 deg ray jitter)
  double plateau_tolerance_deg = 5.0;  // x_p plateau: FOV within this of the best (above the ray jitter)
  double shift_half_range_mm = 4.0;    // bracket half-width around the geometric guess (x2.5 for the source)
  int bracket_points = 17;
  int edge_bisections = 6;
  int border_bisections = 6;
  // Evaluate every bracket point (the reference) instead of walking out from the guess until
  // two consecutive points fall below the plateau level (same result, fewer traces).
  bool full_bracket = false;
};

struct GazeSample {
  double gaze_deg = 0;
  double shift_mm = 0;  // optimal HOE shift (or source shift)
  FovSample fov;
  double pupil_position_mm = 0;            // pupil centre along the axis (bench x for yaw, y for pitch)
  std::array<double, 2> plateau_mm{0, 0};  // shifts whose FOV is within plateau_tolerance_deg of the best
  double best_fov_deg = 0;                 // best FOV of the bracket (F*)
};

struct EyeBox {
  double width_mm = 0;
  std::array<double, 2> pupil_range_mm{0, 0};
  std::array<double, 2> gaze_range_deg{0, 0};
  std::array<double, 2> travel_mm{0, 0};              // optimal shift at the two borders
  bool lower_bounded = false, upper_bounded = false;  // a border was found inside the studied range
  double reference_fov_deg = 0;                       // FOV at zero gaze (with its optimal shift)
};

struct GazeSweepResult {
  GazeAxis axis = GazeAxis::Yaw;
  ShiftMethod method = ShiftMethod::Hoe;
  std::vector<GazeSample> samples;
  EyeBox eyebox;
};

// The FOV along the axis (horizontal for yaw, vertical for pitch).
double axisFov(const FovSample& f, GazeAxis axis);

// The query of a gaze along the axis with a shift of the given method (HOE local x for yaw,
// y for pitch; the source along bench z; nothing for None).
FovQuery gazeQuery(double gaze_deg, GazeAxis axis, ShiftMethod method, double shift_mm);
// The pupil centre along the axis (bench x for yaw, y for pitch) at that gaze.
double pupilPositionMm(const Scene& scene, double gaze_deg, GazeAxis axis);

// Optimal shift for one gaze (see header comment).
GazeSample optimiseShift(const Scene& scene, const FovEvaluator& eval, double gaze_deg, GazeAxis axis,
                         ShiftMethod method, const GazeStudyOptions& options = {});

// The gaze samples from..to by step (inclusive). Throws std::invalid_argument unless from <= to, step > 0.
std::vector<double> sweepGazes(double from_deg, double to_deg, double step_deg);

// Gaze sweep from..to by step (inclusive), each with its optimal shift, plus the eye box
// (borders refined between samples). Parallel over gaze samples; cancellable.
// = optimiseShift at every gaze of sweepGazes() and at zero gaze, then finishSweep().
StudyOutcome<GazeSweepResult> sweepGaze(const Scene& scene, const FovEvaluator& eval, double from_deg, double to_deg,
                                        double step_deg, GazeAxis axis, ShiftMethod method,
                                        const GazeStudyOptions& options = {}, const StudyControl& control = {});

// The eye box of a sweep from its samples (in gaze order) and the zero-gaze reference sample:
// walks out from zero gaze on each side and bisects the first failure (border_bisections).
// A sharded sweep (sweep_shards.h) computes the samples in slices and finishes here.
StudyOutcome<GazeSweepResult> finishSweep(const Scene& scene, const FovEvaluator& eval, std::vector<GazeSample> samples,
                                          const GazeSample& reference, GazeAxis axis, ShiftMethod method,
                                          const GazeStudyOptions& options = {}, const StudyControl& control = {});

struct SensitivitySample {
  double value = 0;
  FovSample fov;
};

// FOV, mean efficiency and uniformity at the scene's gaze over values of one parameter.
StudyOutcome<std::vector<SensitivitySample>> sensitivitySweep(const Scene& scene, const FovEvaluator& eval,
                                                              const std::string& path, double from, double to,
                                                              int steps, const StudyControl& control = {});

}  // namespace fovea
