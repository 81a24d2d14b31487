#pragma once
// Figures read from a retinal image (retina_image.h) for the studio's Retina image mode and the
// design report's caption (issue 29): the lateral colour the image shows at the line of sight.

#include <algorithm>
#include <cmath>
#include <optional>

#include "model/image/retina_image.h"

namespace fovea::image {

// The lasers' dispersion at the line of sight: the largest |offset| of a laser's visual angle from
// the calibration laser's (arcmin; RetinaImageResult::lateral_colour, lateral_colour.h), over the
// lasers whose ray enters the pupil. Nothing when none does.
inline std::optional<double> lineOfSightDispersionArcmin(const RetinaImageResult& r) {
  std::optional<double> largest;
  for (const LateralColour& c : r.lateral_colour)
    if (c.valid) largest = std::max(largest.value_or(0.0), std::hypot(c.offset_arcmin[0], c.offset_arcmin[1]));
  return largest;
}

// The lateral colour the image shows at the line of sight (arcmin, the largest of the lasers):
// with one geometric calibration (the laser nearest 555 nm) each laser shows the calibration's
// content where its own ray lands, so the channels part by the dispersion; with
// per_laser_calibration each laser's content is picked by its own landing angle, so the channels
// stay registered (0). Nothing when no laser's line-of-sight ray enters the pupil.
inline std::optional<double> lateralColourShownArcmin(const RetinaImageResult& r, const RetinaImageOptions& o) {
  const std::optional<double> d = lineOfSightDispersionArcmin(r);
  if (!d) return std::nullopt;
  return o.per_laser_calibration ? 0.0 : *d;
}

}  // namespace fovea::image
