#include "model/analysis/analysis_json.h"

#include "model/analysis/lens_catalog.h"
#include "model/json_numbers.h"

namespace fovea {

namespace {

nlohmann::json fovDegJson(const FovDeg& f) {
  return {{"horizontal", f.horizontal}, {"vertical", f.vertical}, {"diagonal", f.diagonal}};
}

nlohmann::json fovSampleJson(const FovSample& f) {
  return {{"horizontal", f.horizontal_deg}, {"vertical", f.vertical_deg}, {"diagonal", f.diagonal_deg}};
}

nlohmann::json curveJson(const std::vector<SelectivitySample>& c, const char* x_key) {
  nlohmann::json arr = nlohmann::json::array();
  for (const auto& s : c)
    arr.push_back({{x_key, s.x}, {"efficiency", s.efficiency}, {"xi", s.xi}, {"nu", s.nu}, {"entered", s.entered}});
  return arr;
}

}  // namespace

nlohmann::json traceResultJson(const TraceResult& r, const TraceOptions& o, const TraceFov& fov, FovMethod method) {
  nlohmann::json out{{"fov_deg", fovDegJson(fov.shown(method))},
                     {"fov_method", fovMethodName(method)},
                     {"fov_dense_deg", fovDegJson(fov.dense)},
                     {"fov_extent_deg", fovDegJson(fov.extent)},
                     {"rays", r.rays},
                     {"rays_in_pupil", r.rays_in_pupil},
                     {"rays_efficient", r.rays_efficient},
                     {"mean_efficiency", r.mean_efficiency},
                     {"rays_on_hoe", r.rays_on_hoe},
                     {"mean_efficiency_on_hoe", r.mean_efficiency_on_hoe},
                     {"gaze_deg", r.gaze_deg},
                     {"hoe_shift_mm", o.hoe_shift_mm},
                     {"source_shift_mm", o.source_shift_mm},
                     {"efficiency_threshold", o.efficiency_threshold},
                     {"polarization", polarizationName(o.polarization)}};
  nlohmann::json per = nlohmann::json::array();
  for (const auto& w : r.per_wavelength)
    per.push_back({{"wavelength_nm", w.wavelength_nm},
                   {"fov_deg", fovDegJson(w.fov_deg)},
                   {"rays", w.rays},
                   {"rays_in_pupil", w.rays_in_pupil},
                   {"rays_efficient", w.rays_efficient},
                   {"mean_efficiency", w.mean_efficiency}});
  out["per_wavelength"] = per;
  return out;
}

nlohmann::json eyeBoxJson(const EyeBox& eb) {
  return {{"width_mm", eb.width_mm},
          {"pupil_range_mm", eb.pupil_range_mm},
          {"gaze_range_deg", eb.gaze_range_deg},
          {"travel_mm", eb.travel_mm},
          {"lower_border_found", eb.lower_bounded},
          {"upper_border_found", eb.upper_bounded},
          {"reference_fov_deg", eb.reference_fov_deg}};
}

nlohmann::json sweepResultJson(const GazeSweepResult& r, const std::string& axis) {
  nlohmann::json j;
  j["axis"] = axis;
  const ShiftMethod m = r.method;
  const bool source = m == ShiftMethod::Source || m == ShiftMethod::SourceAxial;
  j["method"] = m == ShiftMethod::Hoe ? "hoe" : source ? "source" : "none";
  nlohmann::json arr = nlohmann::json::array();
  for (const auto& s : r.samples)
    arr.push_back(
        {{"gaze_deg", s.gaze_deg},
         {"hoe_shift_mm", m == ShiftMethod::Hoe ? s.shift_mm : 0.0},
         {"source_shift_mm", source ? s.shift_mm : 0.0},
         {"source_z_mm", source ? s.shift_mm : 0.0},
         {"fov_deg", fovSampleJson(s.fov)},
         {"fov_extent_deg", {{"horizontal", s.fov.extent_horizontal_deg}, {"vertical", s.fov.extent_vertical_deg}}},
         {"mean_efficiency", s.fov.mean_efficiency},
         {"efficiency_uniformity", s.fov.efficiency_uniformity},
         {"pupil_position_mm", s.pupil_position_mm},
         {"shift_plateau_mm", s.plateau_mm},
         {"best_fov_deg", s.best_fov_deg},
         {"focus_axial_miss_mm", numberOrNull(s.focus_axial_miss_mm)}});
  j["samples"] = arr;
  j["eyebox_mm"] = r.eyebox.width_mm;
  j["eyebox"] = eyeBoxJson(r.eyebox);
  return j;
}

nlohmann::json compareShiftMethodJson(const EyeBox& eb, ShiftMethod m, GazeAxis ax) {
  const char* shift_axis = m == ShiftMethod::Hoe           ? (ax == GazeAxis::Yaw ? "HOE local x" : "HOE local y")
                           : m == ShiftMethod::Source      ? "projector along bench z"
                           : m == ShiftMethod::SourceAxial ? "projector along its optical axis"
                                                           : "none";
  return {{"gaze_range_deg", eb.gaze_range_deg},
          {"gaze_coverage_deg", eb.gaze_range_deg},
          {"travel_mm", eb.travel_mm},
          {"eyebox_mm", eb.width_mm},
          {"eyebox", eyeBoxJson(eb)},
          {"shift_axis", shift_axis}};
}

nlohmann::json sourceShiftSamplesJson(const std::vector<GazeSample>& samples, GazeAxis ax) {
  nlohmann::json arr = nlohmann::json::array();
  for (const GazeSample& s : samples)
    arr.push_back({{"gaze_deg", s.gaze_deg},
                   {"source_z_mm", s.shift_mm},
                   {"fov_deg", axisFov(s.fov, ax)},
                   {"pupil_position_mm", s.pupil_position_mm}});
  return arr;
}

nlohmann::json compareShiftJson(const EyeBox& hoe, const EyeBox& source, const EyeBox* fixed, GazeAxis ax,
                                ShiftMethod source_method) {
  nlohmann::json j;
  j["hoe_shift"] = compareShiftMethodJson(hoe, ShiftMethod::Hoe, ax);
  j["source_shift"] = compareShiftMethodJson(source, source_method, ax);
  j["eyebox_ratio"] = source.width_mm > 0 ? nlohmann::json(hoe.width_mm / source.width_mm) : nlohmann::json(nullptr);
  if (fixed) {
    j["static"] = compareShiftMethodJson(*fixed, ShiftMethod::None, ax);
    j["hoe_shift"]["gain_mm"] = hoe.width_mm - fixed->width_mm;
    j["source_shift"]["gain_mm"] = source.width_mm - fixed->width_mm;
  }
  return j;
}

nlohmann::json sensitivityResultJson(const std::vector<SensitivitySample>& samples, const std::string& parameter,
                                     double nominal_value) {
  nlohmann::json j;
  j["parameter"] = parameter;
  j["nominal_value"] = nominal_value;
  nlohmann::json arr = nlohmann::json::array();
  for (const auto& s : samples)
    arr.push_back({{"value", s.value},
                   {"fov_deg", fovSampleJson(s.fov)},
                   {"mean_efficiency", s.fov.mean_efficiency},
                   {"efficiency_uniformity", s.fov.efficiency_uniformity},
                   {"rays_in_pupil", s.fov.rays_in_pupil},
                   {"hoe_shift_mm", s.hoe_shift_mm}});
  j["samples"] = arr;
  return j;
}

nlohmann::json resolutionResultJson(const ResolutionResult& r, const Scene& scene) {
  nlohmann::json out;
  out["pixels_horizontal"] = r.pixels_horizontal;
  out["gaze_deg"] = {r.gaze_yaw_deg, r.gaze_pitch_deg};
  out["units"] = "cycles per degree (1 cycle = 2 pixels); angles in degrees";
  out["projector_pixels_per_deg"] = r.projector_pixels_per_deg;
  out["peripheral_field_deg"] = r.peripheral_field_deg;
  out["foveal_field_deg"] = r.foveal_field_deg;
  out["peripheral_pixel_integral"] = r.peripheral_pixel_integral;
  out["peripheral_pixels_on_hoe"] = r.peripheral_pixels_on_hoe;
  out["foveal_pixel_integral"] = r.foveal_pixel_integral;
  out["foveal_pixels_horizontal"] = scene.foveal_display.pixels[0];
  out["eye_limit_cpd"] = kEyeLimitCpd;
  nlohmann::json arr = nlohmann::json::array();
  for (const auto& s : r.samples)
    arr.push_back({{"eccentricity_deg", s.eccentricity_deg},
                   {"foveal_cpd", optionalNumber(s.foveal_cpd)},
                   {"peripheral_cpd", optionalNumber(s.peripheral_cpd)},
                   {"optical_limit_cpd", optionalNumber(s.optical_limit_cpd)},
                   {"optical_limit_model_cpd", optionalNumber(s.optical_limit_model_cpd)},
                   {"optical_blur_arcmin", optionalNumber(s.optical_blur_arcmin)},
                   {"perceived_cpd", s.perceived_cpd},
                   {"foveal_shown", s.foveal_shown}});
  out["samples"] = arr;
  return out;
}

nlohmann::json spotMetricsJson(const SpotMetrics& m) {
  return {{"spot_fwhm_arcmin", m.fwhm_arcmin}, {"cpd_mtf50", m.mtf50_cpd}, {"cpd_mtf10", m.mtf10_cpd}};
}

nlohmann::json peripheralSpotJson(const PeripheralSpot& p) {
  nlohmann::json e = spotMetricsJson(p.metrics);
  e["wavelength_nm"] = p.wavelength_nm;
  e["valid"] = p.valid;
  e["layer"] = p.layer;
  e["throw_mm"] = p.throw_mm;
  e["hoe_to_pupil_mm"] = p.hoe_to_pupil_mm;
  e["hoe_power_d"] = p.hoe_power_d;
  e["lambda_eff_nm"] = p.lambda_eff_nm;
  e["beam_radius_hoe_mm"] = p.beam_radius_hoe_mm;
  e["beam_radius_pupil_mm"] = p.beam_radius_pupil_mm;
  e["pupil_transmission"] = p.pupil_transmission;
  // The HOE's astigmatism (hologram_astigmatism.h): the elliptical spot and the two vergences.
  e["field_deg"] = p.field_deg;
  e["hoe_vergence_d"] = p.vergence_d;
  e["astigmatism_d"] = p.astigmatism_d;
  e["radius_major_arcmin"] = p.radius_major_arcmin;
  e["radius_minor_arcmin"] = p.radius_minor_arcmin;
  e["orientation_deg"] = p.orientation_deg;
  e["cpd_mtf50_long_axis"] = p.metrics_major.mtf50_cpd;
  e["cpd_mtf10_long_axis"] = p.metrics_major.mtf10_cpd;
  return e;
}

nlohmann::json fovealSpotJson(const FovealSpot& f) {
  nlohmann::json e = spotMetricsJson(f.metrics);
  e["wavelength_nm"] = f.wavelength_nm;
  e["defocus_d"] = f.defocus_d;
  e["geometric_blur_arcmin"] = f.geometric_blur_arcmin;
  e["pixel_arcmin"] = f.pixel_arcmin;
  e["combiner_rms_arcmin"] = f.combiner_rms_arcmin;
  e["eye_only"] = spotMetricsJson(f.eye_only);
  return e;
}

nlohmann::json accommodationResolutionJson(const AccommodationResolution& r) {
  nlohmann::json out;
  out["gaze_deg"] = r.gaze_deg;
  out["spot_fwhm_definition"] = "diameter enclosing half the power (EE50): the FWHM of a Gaussian spot";
  out["peripheral_spot_change"] = optionalNumber(r.peripheral_spot_change);
  out["foveal_spot_change"] = optionalNumber(r.foveal_spot_change);
  nlohmann::json arr = nlohmann::json::array();
  for (const auto& s : r.samples) {
    nlohmann::json e;
    e["accommodation_d"] = s.accommodation_d;
    e["distance_cm"] = s.accommodation_d > 0 ? nlohmann::json(100.0 / s.accommodation_d) : nlohmann::json(nullptr);
    const bool have_p = r.peripheral_reference < s.peripheral.size() && s.peripheral[r.peripheral_reference].valid;
    e["peripheral"] = have_p ? spotMetricsJson(s.peripheral[r.peripheral_reference].metrics) : nlohmann::json(nullptr);
    const bool have_f = r.foveal_reference < s.foveal.size();
    e["foveal"] = have_f ? spotMetricsJson(s.foveal[r.foveal_reference].metrics) : nlohmann::json(nullptr);
    e["foveal_defocus_d"] = have_f ? nlohmann::json(s.foveal[r.foveal_reference].defocus_d) : nlohmann::json(nullptr);
    nlohmann::json per = nlohmann::json::array();
    for (const auto& p : s.peripheral) per.push_back(peripheralSpotJson(p));
    e["peripheral_per_wavelength"] = per;
    nlohmann::json fov = nlohmann::json::array();
    for (const auto& f : s.foveal) fov.push_back(fovealSpotJson(f));
    e["foveal_per_primary"] = fov;
    arr.push_back(e);
  }
  out["samples"] = arr;
  return out;
}

nlohmann::json lensOptimizationJson(const LensOptimization& r) {
  nlohmann::json j;
  j["part"] = r.best.lens.part;
  j["vendor"] = r.best.lens.vendor;
  j["shape"] = r.best.lens.shape;
  j["focal_length_mm"] = r.best.lens.focal_length_mm;
  j["diameter_mm"] = r.best.lens.diameter_mm;
  j["center_thickness_mm"] = r.best.lens.center_thickness_mm;
  j["index_d"] = glassIndex(r.best.lens.glass, 587.6);
  j["position_mm"] = r.pose.position_mm;
  j["rotation_deg"] = r.pose.rotation_deg;
  j["tilt_deg"] = r.best.placement.tilt_deg;
  j["distance_mm"] = r.best.placement.distance_mm;
  j["decenter_mm"] = r.best.placement.decenter_mm;
  j["rms_spot_um"] = {{"before", r.rms_before_um}, {"after", r.rms_after_um}};
  j["improvement_percent"] = r.improvement_percent;
  j["distance_bound_mm"] = r.distance_bound_mm;
  nlohmann::json cands = nlohmann::json::array();
  for (const auto& c : r.candidates)
    cands.push_back({{"part", c.lens.part},
                     {"focal_length_mm", c.lens.focal_length_mm},
                     {"diameter_mm", c.lens.diameter_mm},
                     {"distance_mm", c.placement.distance_mm},
                     {"decenter_mm", c.placement.decenter_mm},
                     {"tilt_deg", c.placement.tilt_deg},
                     {"rms_spot_um", c.rms_spot_um},
                     // the candidate's own gain, as the best's improvement_percent (docs/analyses.md)
                     {"improvement_percent", 100.0 * (r.rms_before_um - c.rms_spot_um) / r.rms_before_um},
                     {"evaluations", c.evaluations}});
  j["candidates"] = cands;
  return j;
}

nlohmann::json selectivityResultJson(const SelectivityResult& r) {
  nlohmann::json j;
  j["point_mm"] = r.point_mm;
  nlohmann::json layers = nlohmann::json::array();
  for (const auto& l : r.layers) {
    layers.push_back({{"name", l.name},
                      {"valid", l.valid},
                      {"recording_wavelength_nm", l.recording_wavelength_nm},
                      {"probe_wavelength_nm", l.probe_wavelength_nm},
                      {"incidence_deg", l.incidence_deg},
                      {"nominal_efficiency", l.nominal_efficiency},
                      {"nominal_xi", l.nominal_xi},
                      {"peak_detuning_deg", l.peak_detuning_deg},
                      {"peak_angle_efficiency", l.peak_angle_efficiency},
                      {"angular_fwhm_deg", optionalNumber(l.angular_fwhm_deg)},
                      {"peak_wavelength_nm", l.peak_wavelength_nm},
                      {"peak_spectral_efficiency", l.peak_spectral_efficiency},
                      {"spectral_fwhm_nm", optionalNumber(l.spectral_fwhm_nm)},
                      {"angle", curveJson(l.angle, "detuning_deg")},
                      {"spectrum", curveJson(l.spectrum, "wavelength_nm")}});
  }
  j["layers"] = layers;
  return j;
}

nlohmann::json kogelnikVsRcwaJson(const std::vector<rigorous::KogelnikRcwaPoint>& points) {
  nlohmann::json pts = nlohmann::json::array();
  for (const auto& p : points)
    pts.push_back({{"geometry", p.geometry},
                   {"thickness_um", p.grating.thickness_um},
                   {"n1", p.grating.n1},
                   {"period_nm", p.grating.period_nm},
                   {"xi_target", p.xi_target},
                   {"detuning_deg", p.detuning_deg},
                   {"rho", p.rho},
                   {"klein_q", p.klein_q},
                   {"kogelnik_efficiency", p.kogelnik.efficiency},
                   {"nu", p.kogelnik.nu},
                   {"rcwa_efficiency", p.rcwa_efficiency},
                   {"rcwa_converged", p.rcwa_converged},
                   {"abs_error", p.abs_error},
                   {"abs_error_linearised", p.abs_error_linearised},
                   {"kogelnik_ns", p.kogelnik_ns},
                   {"rcwa_ms", p.rcwa_ms},
                   {"rcwa_single_ms", p.rcwa_single_ms}});
  nlohmann::json bins = nlohmann::json::array();
  for (const auto& b : rigorous::summariseByRho(points))
    bins.push_back({{"rho_min", b.rho_min},
                    {"rho_max", b.rho_max < 1e299 ? nlohmann::json(b.rho_max) : nlohmann::json(nullptr)},
                    {"points", b.points},
                    {"max_error", b.max_error},
                    {"median_error", b.median_error},
                    {"max_error_weak", b.max_error_weak},
                    {"max_error_linearised", b.max_error_linearised},
                    {"mean_kogelnik_ns", b.mean_kogelnik_ns},
                    {"mean_rcwa_ms", b.mean_rcwa_ms}});
  return {{"points", pts}, {"by_rho", bins}};
}

}  // namespace fovea
