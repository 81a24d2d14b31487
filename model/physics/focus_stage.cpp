#include "model/physics/focus_stage.h"

#include <cmath>
#include <limits>

#include <Eigen/Core>

namespace fovea {

FocusStageModel focusStageModel(const Scene& scene) {
  const CombinerPrescription c = combinerPrescription(scene);
  return {c.mirror_distance_mm, c.focal_length_mm, c.display_distance_mm};
}

double imageDistanceForPanel(const FocusStageModel& m, double panel_mm) {
  const double f = m.focal_length_mm;
  if (panel_mm >= f) return std::numeric_limits<double>::infinity();
  return m.mirror_distance_mm + panel_mm * f / (f - panel_mm);
}

double panelForImageDistance(const FocusStageModel& m, double image_mm) {
  const double v = image_mm - m.mirror_distance_mm;
  return v * m.focal_length_mm / (v + m.focal_length_mm);
}

double dioptresPerMm(const FocusStageModel& m, double panel_mm) {
  const double f = m.focal_length_mm, d = imageDistanceForPanel(m, panel_mm);
  return -(1000.0 / (d * d)) * f * f / ((f - panel_mm) * (f - panel_mm));
}

double focusAxisForImageDistance(const FocusStageModel& m, double image_mm) {
  return m.nominal_panel_mm - panelForImageDistance(m, image_mm);
}

double imageDistanceForFocusAxis(const FocusStageModel& m, double axis_mm) {
  return imageDistanceForPanel(m, m.nominal_panel_mm - axis_mm);
}

FocusTravel focusTravel(const FocusStageModel& m, double near_mm, double far_mm) {
  FocusTravel t;
  t.near_mm = near_mm;
  t.far_mm = far_mm;
  t.panel_near_mm = panelForImageDistance(m, near_mm);
  t.panel_far_mm = panelForImageDistance(m, far_mm);
  t.travel_mm = std::abs(t.panel_far_mm - t.panel_near_mm);
  t.range_d = 1000.0 / near_mm - 1000.0 / far_mm;
  t.sensitivity_near_d_per_mm = std::abs(dioptresPerMm(m, t.panel_near_mm));
  t.sensitivity_far_d_per_mm = std::abs(dioptresPerMm(m, t.panel_far_mm));
  return t;
}

double focusImageDistanceTraced(const FocusStageModel& m, double panel_mm, double zone_mm) {
  const CombinerPrescription c{m.mirror_distance_mm, m.focal_length_mm, panel_mm};
  const Eigen::Vector3d p(zone_mm, 0, 0);
  // Signed panel-plane height of the ray aimed at the axial point at distance d.
  auto height = [&](double d) {
    const auto hit = traceCombinerToDisplay(c, p, Eigen::Vector3d(0, 0, d));
    return hit ? hit->x() : std::numeric_limits<double>::quiet_NaN();
  };
  const double paraxial = imageDistanceForPanel(m, panel_mm);
  // Bisection in vergence 1/d between a quarter and four times the paraxial image distance
  // (measured behind the mirror).
  const double v = paraxial - m.mirror_distance_mm;
  double lo = 1.0 / (m.mirror_distance_mm + 4 * v), hi = 1.0 / (m.mirror_distance_mm + 0.25 * v);
  const double h_lo = height(1 / lo);
  if (!std::isfinite(h_lo) || !std::isfinite(height(1 / hi))) return std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double h = height(1 / mid);
    if (!std::isfinite(h)) return std::numeric_limits<double>::quiet_NaN();
    ((h > 0) == (h_lo > 0) ? lo : hi) = mid;
  }
  return 2.0 / (lo + hi);
}

}  // namespace fovea
