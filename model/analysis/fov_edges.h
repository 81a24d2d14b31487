#pragma once
// The continuous FOV (trace_evaluator.h) with its edges found by root-finding instead of by
// counting dense samples, so its error is set by a tolerance, not by the ray count.
//
// The dense estimator walks, per wavelength, the projector-grid row and column through the
// line of sight (the lit ray nearest the field centre) and keeps the widest run of
// consecutive lit rays (in the pupil, efficiency >= threshold). Its limit as the grid gets
// finer is what is computed here, with single rays (model/physics/ray_probe.h):
//  1. line of sight: the lit ray of a coarse grid nearest the field centre, refined by
//     Newton's method on field(tan_x, tan_y) = (0, 0) (finite-difference Jacobian) while the
//     refined ray stays lit;
//  2. along the row (tan_y fixed) and the column (tan_x fixed) through it, scan_samples
//     equally spaced samples over the plate's image in the projector field (no ray outside it
//     meets the plate; RayProbe::plateBoundsTan(), clipped to the field) bracket the lit
//     runs; every edge between a lit and a dark sample is bisected until the field angle
//     is known to tolerance_deg. "Lit" is one predicate, so the three kinds of edge — the
//     efficiency threshold, the pupil entry and the plate edge — are found alike; an edge
//     at the projector's field edge is that edge (the dense grid's outer pixel centres
//     tend to it);
//  3. the widest run's field-angle span is the FOV along that line; the diagonal is the angle
//     between the corners of the two spans; the smallest over the wavelengths is kept.
// Limits (its "discretisation"): a dark hole or a lit island narrower than the scan spacing
// (the plate's image / (scan_samples - 1): ~1.4 deg of field on the prototype) between two
// samples is not seen; a dense grid finer than that would see it.
//
// The coarse grid (over the plate's image) also gives the sample statistics (rays in the
// pupil, mean efficiency, uniformity, lit extent): of that grid, not of a `rays`-dense one.

#include <array>
#include <vector>

#include "model/analysis/trace_evaluator.h"
#include "model/physics/ray_probe.h"

namespace fovea {

struct EdgeFovOptions {
  FovAngle angle = FovAngle::Arrival;  // trace_evaluator.h
  double efficiency_threshold = 0.1;
  double tolerance_deg = 0.005;            // each edge's field angle to this
  int scan_samples = 49;                   // bracketing samples along each scan line
  std::array<int, 2> coarse_grid{24, 14};  // line-of-sight search and statistics (columns, rows)
  // Scan the row (horizontal FOV) and the column (vertical); a skipped line gives a FOV of 0
  // along it and no diagonal, the other one's is unchanged (it never reads the skipped one).
  std::array<bool, 2> scan_lines{true, true};
};

struct EdgeFovResult {
  ContinuousFov fov;
  FovDeg extent;  // lit extent (max - min) of the coarse-grid rays over all wavelengths (diagonal not set)
  double mean_efficiency = 0, efficiency_uniformity = 0;  // coarse-grid rays in the pupil
  int rays_in_pupil = 0;
  long long rays_traced = 0;
};

EdgeFovResult edgeFov(const RayProbe& probe, const std::vector<double>& wavelengths_nm,
                      const EdgeFovOptions& options = {});

}  // namespace fovea
