#include "model/gaze/fixation_gazes.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "model/scene/scene_geometry.h"
#include "model/units.h"

namespace fovea::gaze {

namespace {

void requireDistance(const BinocularGeometry& g, double distance_mm) {
  if (!(distance_mm > g.ipd_mm / 2) || !std::isfinite(distance_mm))
    throw std::invalid_argument("fixation distance " + std::to_string(distance_mm) +
                                " mm: must exceed half the interpupillary distance (" + std::to_string(g.ipd_mm / 2) +
                                " mm)");
}

FixationGazes gazesTowards(const BinocularGeometry& g, const Eigen::Vector3d& p) {
  FixationGazes out;
  out.point = p;
  out.distance_mm = p.norm();
  out.direction_deg = gazeTowardsDeg(Eigen::Vector3d::Zero(), p);
  out.left_deg = gazeTowardsDeg(g.leftCentre(), p);
  out.right_deg = gazeTowardsDeg(g.rightCentre(), p);
  const Eigen::Vector3d dl = (p - g.leftCentre()).normalized(), dr = (p - g.rightCentre()).normalized();
  out.vergence_deg = radToDeg(std::atan2(dl.cross(dr).norm(), dl.dot(dr)));
  return out;
}

}  // namespace

FixationGazes gazesFixating(const BinocularGeometry& g, const std::array<double, 2>& direction_deg,
                            double distance_mm) {
  requireDistance(g, distance_mm);
  return gazesTowards(g, distance_mm * gazeDirection(direction_deg[0], direction_deg[1]));
}

FixationGazes fixationOnRightGaze(const BinocularGeometry& g, const std::array<double, 2>& right_deg,
                                  double distance_mm) {
  requireDistance(g, distance_mm);
  const Eigen::Vector3d c = g.rightCentre(), d = gazeDirection(right_deg[0], right_deg[1]);
  const double b = c.dot(d);
  const double t = -b + std::sqrt(b * b + distance_mm * distance_mm - c.squaredNorm());
  FixationGazes out = gazesTowards(g, c + t * d);
  out.right_deg = right_deg;  // the given gaze itself, not its round trip through the point
  return out;
}

}  // namespace fovea::gaze
