#pragma once
// JSON forms of the analysis results, with the keys of the fovea-cli commands' --json output
// (trace, sweep, compare-shift, sensitivity, resolution, optimize-lens, selectivity) so the
// studio, its plots and its reports read the very same documents as the CLI. The GUI test
// tests/gui/tst_analyses_panel.cpp checks the key sets against the CLI's output.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/analysis/accommodation_resolution.h"
#include "model/analysis/angular_resolution.h"
#include "model/analysis/beam_shaping.h"
#include "model/analysis/gaze_studies.h"
#include "model/analysis/hoe_selectivity.h"
#include "model/analysis/retinal_psf.h"
#include "model/analysis/trace_fov.h"
#include "model/physics/trace.h"
#include "model/rigorous/kogelnik_vs_rcwa.h"

namespace fovea {

// fov_deg: the FOV of `method` (trace_fov.h; edges, the exact one, by default), beside
// fov_method, fov_dense_deg (the dense continuous FOV) and fov_extent_deg (the lit extent).
nlohmann::json traceResultJson(const TraceResult& r, const TraceOptions& o, const TraceFov& fov, FovMethod method);
nlohmann::json sweepResultJson(const GazeSweepResult& r, const std::string& axis);
// One method's part of compare-shift ("hoe_shift" / "source_shift" values).
nlohmann::json compareShiftMethodJson(const EyeBox& eb, ShiftMethod method, GazeAxis axis);
// The whole compare-shift document: both methods and "eyebox_ratio"; with the static eye box
// (nothing moving) also "static" and each method's "gain_mm" over it.
nlohmann::json compareShiftJson(const EyeBox& hoe, const EyeBox& source, const EyeBox* fixed, GazeAxis axis,
                                ShiftMethod source_method = ShiftMethod::Source);
// The source method's per-gaze samples: gaze_deg, source_z_mm (its optimal shift), fov_deg.
nlohmann::json sourceShiftSamplesJson(const std::vector<GazeSample>& samples, GazeAxis axis);
nlohmann::json eyeBoxJson(const EyeBox& eb);
nlohmann::json sensitivityResultJson(const std::vector<SensitivitySample>& samples, const std::string& parameter,
                                     double nominal_value);
nlohmann::json resolutionResultJson(const ResolutionResult& r, const Scene& scene);
// The resolution command's "accommodation" part (--accommodation-d): per accommodation the
// reference peripheral and foveal {spot_fwhm_arcmin, cpd_mtf50, cpd_mtf10} (retina-image's
// keys), the distance focused, the foveal defocus and every wavelength's values.
nlohmann::json accommodationResolutionJson(const AccommodationResolution& r);
// A retinal spot as {spot_fwhm_arcmin, cpd_mtf50, cpd_mtf10} (the keys of issue 29's contract:
// retina-image's "peripheral"/"foveal" and resolution's "accommodation").
nlohmann::json spotMetricsJson(const SpotMetrics& m);
// One laser's peripheral spot / one primary's foveal spot: the metrics and how they arose
// (retina-image's peripheral_per_wavelength / foveal_per_primary, resolution's per sample).
nlohmann::json peripheralSpotJson(const PeripheralSpot& p);
nlohmann::json fovealSpotJson(const FovealSpot& f);
nlohmann::json lensOptimizationJson(const LensOptimization& r);
nlohmann::json selectivityResultJson(const SelectivityResult& r);
// {"points":[...every grid point...], "by_rho":[...summariseByRho rows...]}
nlohmann::json kogelnikVsRcwaJson(const std::vector<rigorous::KogelnikRcwaPoint>& points);

}  // namespace fovea
