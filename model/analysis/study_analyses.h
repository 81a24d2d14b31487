#pragma once
// The registry definitions of the scene studies (trace, sweep, compare-shift, sensitivity,
// resolution, optimize-lens, selectivity) and of the planar-grating analyses, and the
// option builders the fovea-cli commands share with them (values validated by
// validateValues, analysis_registry.h).

#include <nlohmann/json.hpp>

#include "model/analysis/analysis_registry.h"
#include "model/analysis/gaze_studies.h"
#include "model/analysis/hoe_selectivity.h"
#include "model/analysis/trace_evaluator.h"
#include "model/physics/trace.h"

namespace fovea::analysis {

AnalysisDefinition traceAnalysis();
AnalysisDefinition sweepAnalysis();
AnalysisDefinition compareShiftAnalysis();
AnalysisDefinition sensitivityAnalysis();
AnalysisDefinition resolutionAnalysis();
AnalysisDefinition optimizeLensAnalysis();
AnalysisDefinition selectivityAnalysis();
AnalysisDefinition gratingSweepAnalysis();
AnalysisDefinition kogelnikVsRcwaAnalysis();

// "rays" and "tolerance-deg" of the tracer-backed gaze studies.
std::vector<ParameterSpec> studyParameters();

TraceOptions traceOptionsFrom(const nlohmann::json& values);
// The trace's "fov-method": which FOV is its fov_deg (trace_fov.h; edges by default).
FovMethod traceFovMethodFrom(const nlohmann::json& values);
// The gaze of "gaze-yaw"/"gaze-pitch": nothing when both are unset (the scene's gaze).
std::optional<std::array<double, 2>> gazeFrom(const nlohmann::json& values);
FovEvaluator evaluatorFrom(const nlohmann::json& values);
GazeStudyOptions gazeStudyOptionsFrom(const nlohmann::json& values);
GazeAxis axisFrom(const nlohmann::json& values);
ShiftMethod sweepMethodFrom(const nlohmann::json& values);  // the sweep's "method"
// The sweep analysis' document (fovea-cli sweep --json without "cached") of a result.
nlohmann::json sweepDocument(const GazeSweepResult& result, const nlohmann::json& values);
SelectivityOptions selectivityOptionsFrom(const nlohmann::json& values);

// compare-shift's three eye boxes (HOE shift, source shift, nothing moving) as its document.
std::optional<nlohmann::json> compareShiftStudy(const Scene& scene, const nlohmann::json& values,
                                                const StudyControl& control);

}  // namespace fovea::analysis
