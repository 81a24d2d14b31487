#pragma once
// Chromaticity gamut geometry: the overlapped gamut of two displays (intersection of their
// primary triangles in CIE xy, seed B.2.2 / Fig. S15) and common primaries inside it.

#include <array>
#include <vector>

#include "model/color/colorimetry.h"

namespace fovea::color {

using Triangle = std::array<Xy, 3>;  // R, G, B

double signedArea(const std::vector<Xy>& polygon);
double triangleArea(const Triangle& t);
// Intersection of two triangles (convex, either orientation): a counter-clockwise convex
// polygon, empty when they do not overlap (Sutherland-Hodgman clipping).
std::vector<Xy> intersectTriangles(const Triangle& a, const Triangle& b);
bool insideTriangle(const Triangle& t, Xy p, double tolerance = 1e-12);

// Common primaries: the largest-area triangle inscribed in the convex `overlap` polygon.
// The maximum-area triangle inscribed in a convex polygon has its vertices at polygon
// vertices (area is linear along each edge, so a vertex can always slide to an end), so
// an exhaustive search over vertex triples is exact. Its vertices are then labelled R, G, B
// by the assignment closest (sum of xy distances) to `reference` (e.g. the midpoints of the
// two displays' own primaries).
Triangle largestInscribedTriangle(const std::vector<Xy>& overlap, const Triangle& reference);

}  // namespace fovea::color
