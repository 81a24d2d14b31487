#pragma once
// The planar-grating studies of the analyses panel: one volume grating swept over the probe
// angle with Kogelnik's closed forms and optionally converged RCWA beside them, and the
// Kogelnik-vs-RCWA error/time map of docs/benchmarks.md run one geometry at a time so that
// a cancel request is honoured between them.

#include <optional>

#include <nlohmann/json.hpp>

#include "model/analysis/study_runner.h"
#include "model/physics/grating_request.h"
#include "model/rigorous/kogelnik_vs_rcwa.h"

namespace fovea {

struct ProbeSweepOptions {
  double span_deg = 5.0;  // probe angles centre - span .. centre + span (the request's probe is the centre)
  int samples = 201;
  bool with_rcwa = false;
};

// {"center": the kogelnik document of the request, "models": ["kogelnik"(,"rcwa")],
//  "samples": [{"probe_deg","detuning_deg","kogelnik_efficiency","xi","nu"(,"rcwa_efficiency",
//  "rcwa_converged")}]}. Probe angles at or beyond grazing give null efficiencies. Throws
// std::invalid_argument when the request itself is invalid. Nothing when cancelled.
std::optional<nlohmann::json> probeAngleSweep(const GratingRequest& request, const ProbeSweepOptions& options,
                                              const StudyControl& control = {});

// kogelnikVsRcwaJson of the whole grid plus "grid": `grid_name`. Nothing when cancelled.
std::optional<nlohmann::json> kogelnikVsRcwaStudy(const rigorous::KogelnikRcwaGrid& grid, const std::string& grid_name,
                                                  const StudyControl& control = {});

}  // namespace fovea
