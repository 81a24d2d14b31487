#include "viz/label_placement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace fovea::viz {

namespace {
constexpr double kLeader_px = 30.0;  // shortest anchor-to-label distance
constexpr double kStep_px = 14.0;    // longer leaders, one step per ring of candidates
constexpr int kRings = 14;
constexpr int kDirections = 16;
constexpr double kGap_px = 3.0;  // free space kept between two labels, and around the triad

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}
}  // namespace

double LabelRect::overlapArea(const LabelRect& o) const {
  const double w = std::min(x1, o.x1) - std::max(x0, o.x0), h = std::min(y1, o.y1) - std::max(y0, o.y0);
  return w > 0 && h > 0 ? w * h : 0.0;
}

bool segmentsCross(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& q0,
                   const Eigen::Vector2d& q1) {
  // Proper intersection by orientation tests (shared end points do not count).
  const Eigen::Vector2d r = p1 - p0, s = q1 - q0;
  const double d = cross2(r, s);
  if (std::abs(d) < 1e-12) return false;  // parallel
  const double t = cross2(q0 - p0, s) / d, u = cross2(q0 - p0, r) / d;
  return t > 1e-6 && t < 1 - 1e-6 && u > 1e-6 && u < 1 - 1e-6;
}

bool segmentCrossesRect(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const LabelRect& r) {
  if (r.contains(p0) || r.contains(p1)) return true;
  const Eigen::Vector2d c[4] = {{r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}};
  for (int i = 0; i < 4; ++i)
    if (segmentsCross(p0, p1, c[i], c[(i + 1) % 4])) return true;
  return false;
}

std::vector<PlacedLabel> placeLabels(const std::vector<LabelRequest>& labels, const LabelRect& viewport,
                                     const std::vector<LabelRect>& obstacles, double scale) {
  const std::size_t n = labels.size();
  std::vector<PlacedLabel> out(n);
  if (n == 0) return out;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const LabelRequest& l : labels) centre += l.anchor;
  centre /= static_cast<double>(n);
  // Crowded first: the label whose anchor has the nearest other anchor.
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      if (i != j) nearest[i] = std::min(nearest[i], (labels[i].anchor - labels[j].anchor).norm());
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return nearest[a] < nearest[b]; });

  std::vector<bool> done(n, false);
  const double gap = kGap_px * scale;
  for (const std::size_t i : order) {
    const LabelRequest& l = labels[i];
    Eigen::Vector2d outward = l.anchor - centre;
    outward = outward.norm() < 1e-6 ? Eigen::Vector2d(0.0, 1.0) : outward.normalized();
    double bestCost = std::numeric_limits<double>::infinity(), bestOverlap = bestCost, leastBadCost = bestCost;
    PlacedLabel best, leastBad;
    for (int ring = 0; ring < kRings; ++ring) {
      const double dist = (kLeader_px + ring * kStep_px) * scale;
      for (int k = 0; k < kDirections; ++k) {
        const double a = 2.0 * M_PI * k / kDirections;
        const Eigen::Vector2d dir(std::cos(a), std::sin(a));
        const Eigen::Vector2d at = l.anchor + dist * dir;
        // The box hangs off the leader's end: beside it when the leader is mostly sideways,
        // above or below it (centred) when mostly vertical.
        LabelRect box;
        if (std::abs(dir.x()) >= 0.38) {
          box.x0 = dir.x() > 0 ? at.x() : at.x() - l.width;
          box.y0 = at.y() - l.height / 2;
        } else {
          box.x0 = at.x() - l.width / 2;
          box.y0 = dir.y() > 0 ? at.y() : at.y() - l.height;
        }
        box.x1 = box.x0 + l.width;
        box.y1 = box.y0 + l.height;
        if (box.x0 < viewport.x0 || box.x1 > viewport.x1 || box.y0 < viewport.y0 || box.y1 > viewport.y1) continue;
        const Eigen::Vector2d end(std::clamp(l.anchor.x(), box.x0, box.x1), std::clamp(l.anchor.y(), box.y0, box.y1));
        double overlap = 0.0;
        for (const LabelRect& o : obstacles)
          if (box.overlaps(o, gap)) overlap += 1.0 + box.overlapArea(o);
        for (std::size_t j = 0; j < n; ++j)
          if (done[j] && box.overlaps(out[j].box, gap)) overlap += 1.0 + box.overlapArea(out[j].box);
        // Cost: leader length, direction (away from the middle, then sideways-up), crossings.
        double cost = dist / scale + 28.0 * (1.0 - dir.dot(outward)) + 6.0 * (1.0 - std::abs(dir.x())) +
                      (dir.y() < 0 ? 4.0 : 0.0);
        for (std::size_t j = 0; j < n; ++j) {
          if (j == i) continue;
          if (box.contains(labels[j].anchor)) cost += 60.0;
          if (!done[j]) continue;
          if (segmentCrossesRect(l.anchor, end, out[j].box)) cost += 80.0;
          if (segmentsCross(l.anchor, end, labels[j].anchor, out[j].leaderEnd)) cost += 50.0;
          if (segmentCrossesRect(labels[j].anchor, out[j].leaderEnd, box)) cost += 80.0;
        }
        for (const LabelRect& o : obstacles)
          if (segmentCrossesRect(l.anchor, end, o)) cost += 20.0;
        if (overlap == 0.0 && cost < bestCost) {
          bestCost = cost;
          best = {box, end};
        }
        if (overlap < bestOverlap || (overlap == bestOverlap && cost < leastBadCost)) {
          bestOverlap = overlap;
          leastBadCost = cost;
          leastBad = {box, end};
        }
      }
    }
    if (std::isfinite(bestCost)) {
      out[i] = best;
    } else if (std::isfinite(bestOverlap)) {
      out[i] = leastBad;
    } else {  // not even one candidate inside the viewport: at the anchor, clamped
      LabelRect box{l.anchor.x(), l.anchor.y() - l.height / 2, l.anchor.x() + l.width, l.anchor.y() + l.height / 2};
      const double dx = std::min(0.0, viewport.x1 - box.x1) + std::max(0.0, viewport.x0 - box.x0);
      box.x0 += dx;
      box.x1 += dx;
      out[i] = {box, l.anchor};
    }
    done[i] = true;
  }
  return out;
}

}  // namespace fovea::viz
