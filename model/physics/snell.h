#pragma once
// Snell's law in vector form, for any Eigen vector (2-D meridional traces, 3-D lens traces):
// the component of n d along the surface is kept, so with the unit normal `normal` facing the
// incoming ray (normal . d < 0), eta = n_from / n_to, cos_i = -normal . d:
//   d' = eta d + (eta cos_i - cos_t) normal,   cos_t = sqrt(1 - eta^2 (1 - cos_i^2))
// (Born & Wolf 1.5; Glassner, "An Introduction to Ray Tracing", ch. 4). Empty past the
// critical angle (total internal reflection).

#include <cmath>
#include <optional>

namespace fovea {

template <class Vector>
struct Refraction {
  Vector direction;  // unit when d is
  double cos_in = 1, cos_out = 1;
};

template <class Vector>
std::optional<Refraction<Vector>> refractDirection(const Vector& d, const Vector& normal, double n_from, double n_to) {
  const double eta = n_from / n_to, cos_i = -normal.dot(d);
  const double k = 1 - eta * eta * (1 - cos_i * cos_i);
  if (k < 0) return std::nullopt;
  const double cos_t = std::sqrt(k);
  return Refraction<Vector>{Vector(eta * d + (eta * cos_i - cos_t) * normal), cos_i, cos_t};
}

}  // namespace fovea
