#include "model/color/gamut.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fovea::color {

namespace {
double cross(Xy o, Xy a, Xy b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}
std::vector<Xy> ccw(const Triangle& t) {
  std::vector<Xy> p(t.begin(), t.end());
  if (signedArea(p) < 0) std::reverse(p.begin(), p.end());
  return p;
}
}  // namespace

double signedArea(const std::vector<Xy>& polygon) {
  double a = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Xy& p = polygon[i];
    const Xy& q = polygon[(i + 1) % polygon.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5 * a;
}

double triangleArea(const Triangle& t) {
  return std::abs(0.5 * cross(t[0], t[1], t[2]));
}

std::vector<Xy> intersectTriangles(const Triangle& a, const Triangle& b) {
  std::vector<Xy> out = ccw(a);
  const std::vector<Xy> clip = ccw(b);
  for (std::size_t e = 0; e < clip.size() && !out.empty(); ++e) {
    const Xy c0 = clip[e], c1 = clip[(e + 1) % clip.size()];
    std::vector<Xy> in;
    in.swap(out);
    for (std::size_t i = 0; i < in.size(); ++i) {
      const Xy p = in[i], q = in[(i + 1) % in.size()];
      const double dp = cross(c0, c1, p), dq = cross(c0, c1, q);
      if (dp >= 0) out.push_back(p);
      if ((dp >= 0) != (dq >= 0)) {
        const double t = dp / (dp - dq);
        out.push_back({p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)});
      }
    }
  }
  // Drop duplicate vertices (edges that touch).
  std::vector<Xy> clean;
  for (const Xy& p : out)
    if (clean.empty() || std::hypot(p.x - clean.back().x, p.y - clean.back().y) > 1e-12) clean.push_back(p);
  while (clean.size() > 1 && std::hypot(clean.front().x - clean.back().x, clean.front().y - clean.back().y) <= 1e-12)
    clean.pop_back();
  if (clean.size() < 3 || std::abs(signedArea(clean)) < 1e-14) return {};
  return clean;
}

bool insideTriangle(const Triangle& t, Xy p, double tolerance) {
  const auto v = ccw(t);
  for (std::size_t i = 0; i < 3; ++i)
    if (cross(v[i], v[(i + 1) % 3], p) < -tolerance) return false;
  return true;
}

Triangle largestInscribedTriangle(const std::vector<Xy>& overlap, const Triangle& reference) {
  const std::size_t n = overlap.size();
  Triangle best{};
  double bestArea = -1;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        const Triangle t{overlap[i], overlap[j], overlap[k]};
        const double area = triangleArea(t);
        if (area > bestArea * (1.0 + 1e-12)) {
          bestArea = area;
          best = t;
        }
      }
  // Label the vertices R, G, B: the permutation nearest to the reference primaries.
  std::array<int, 3> perm{0, 1, 2}, bestPerm = perm;
  double bestCost = std::numeric_limits<double>::infinity();
  do {
    double cost = 0;
    for (int c = 0; c < 3; ++c) cost += std::hypot(best[perm[c]].x - reference[c].x, best[perm[c]].y - reference[c].y);
    if (cost < bestCost) {
      bestCost = cost;
      bestPerm = perm;
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return {best[bestPerm[0]], best[bestPerm[1]], best[bestPerm[2]]};
}

}  // namespace fovea::color
