#pragma once
// The FOV evaluator of the gaze studies backed by the HOE ray tracer (model/physics/trace.h).
//
// The studies use the *continuous* FOV, not the tracer's extent (max - min of the lit field
// angles): when the Maxwellian focus is blurred or Bragg mismatch darkens parts of the
// plate, scattered rays can still reach the pupil from both ends of the field while most
// pixels in between are dark (the seed's "blind regions", A.3). Per wavelength, along the
// projector-grid row through the line of sight (that of the lit ray nearest the field
// centre) the widest run of consecutive lit rays (in the pupil, efficiency >= threshold)
// gives the horizontal FOV, along that column the vertical one (the seed's top and side
// views); the smallest over the wavelengths is kept (the field shown in every colour).
// Diagonal: the angle between the corners of those spans.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "model/analysis/gaze_studies.h"
#include "model/physics/trace.h"

namespace fovea {

// How the continuous FOV is estimated: Dense counts runs of lit rays in a `rays`-dense trace
// (its error is about a ray spacing); Edges root-finds the edges of the same runs with single
// rays (fov_edges.h; its error is edge_tolerance_deg, whatever `rays`).
enum class FovMethod { Dense, Edges };
const char* fovMethodName(FovMethod m);  // "dense", "edges"
std::optional<FovMethod> parseFovMethod(const std::string& name);

// Which angle of a lit ray spans the FOV: Arrival, its direction entering the eye (ours: the
// visual angle); Footprint, the direction of its plate point seen from the pupil centre (the
// seed's, ProbeRay::footprint_deg). They agree when the Maxwellian focus sits on the pupil centre.
enum class FovAngle { Arrival, Footprint };

const char* fovDefinitionName(FovAngle a);  // "ours", "seed"
std::optional<FovAngle> parseFovDefinition(const std::string& name);

struct TraceEvaluatorOptions {
  int rays = 12000;                     // rays per wavelength over the projector field (Dense)
  std::optional<double> wavelength_nm;  // default: all projector wavelengths
  double efficiency_threshold = 0.1;
  FovMethod fov_method = FovMethod::Dense;
  double edge_tolerance_deg = 0.005;  // Edges: each edge's field angle to this
  // Which angle spans the FOV (fov_edges.h): Footprint (the seed's) needs the Edges estimator.
  FovAngle fov_angle = FovAngle::Arrival;
};

struct ContinuousFov {
  double horizontal_deg = 0, vertical_deg = 0, diagonal_deg = 0;
};
ContinuousFov continuousFov(const std::vector<TracedRay>& rays, double efficiency_threshold);
ContinuousFov continuousFov(const std::vector<FieldRay>& rays, double efficiency_threshold);  // the same, leaner

// Unit arrival direction of a field angle (yaw = atan2(x, z), pitch = asin(y); fieldAngleDeg())
// and the angle between two such directions: the diagonal between the corners of the spans.
Eigen::Vector3d fieldDirection(const std::array<double, 2>& field_deg);
double spanDiagonalDeg(const std::array<double, 2>& corner_a_deg, const std::array<double, 2>& corner_b_deg);

// Always true since the tracer landed (kept for callers written before it).
inline bool traceEvaluatorAvailable() {
  return true;
}

// Throws std::invalid_argument for the Footprint angle with the Dense estimator.
FovEvaluator traceEvaluator(const TraceEvaluatorOptions& options = {});

}  // namespace fovea
