#pragma once
// Where the 3-D view's element labels go on screen (pure geometry in display pixels, no VTK):
// each label is tried at candidate spots around its anchor (16 directions, growing leader
// lengths) and put at the cheapest spot that overlaps no label placed before it and no
// obstacle (the axes triad), inside the viewport. The cost prefers short leaders pointing away
// from the bench's middle and sideways-up, and penalises a leader that crosses another label
// or leader and a label that covers another element's anchor. Labels are placed in order of
// crowding (the anchor with the nearest neighbour first), so the crowded ones get the best
// spots. When no spot is free (a tiny view), the spot with the least overlap is used.

#include <vector>

#include <Eigen/Core>

namespace fovea::viz {

struct LabelRect {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool overlaps(const LabelRect& o, double margin = 0.0) const {
    return x0 - margin < o.x1 && o.x0 - margin < x1 && y0 - margin < o.y1 && o.y0 - margin < y1;
  }
  double overlapArea(const LabelRect& o) const;
  bool contains(const Eigen::Vector2d& p) const { return p.x() >= x0 && p.x() <= x1 && p.y() >= y0 && p.y() <= y1; }
};

struct LabelRequest {
  Eigen::Vector2d anchor = Eigen::Vector2d::Zero();  // display pixels, y up
  double width = 0, height = 0;
};

struct PlacedLabel {
  LabelRect box;
  Eigen::Vector2d leaderEnd = Eigen::Vector2d::Zero();  // where the leader from the anchor meets the box
};

// `scale`: pixels per logical pixel (the leader lengths and gaps scale with it).
std::vector<PlacedLabel> placeLabels(const std::vector<LabelRequest>& labels, const LabelRect& viewport,
                                     const std::vector<LabelRect>& obstacles, double scale = 1.0);

// Whether segment p0-p1 crosses (or touches) the rectangle / the segment q0-q1.
bool segmentCrossesRect(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const LabelRect& r);
bool segmentsCross(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& q0,
                   const Eigen::Vector2d& q1);

}  // namespace fovea::viz
