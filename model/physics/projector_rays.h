#pragma once
// The projector as a ray source (seed A.1, A.2.1): a point source at the exit pupil centre
// that sends one ray per pixel of a grid over its horizontal x vertical FOV, one grid per
// wavelength. The grid is that of a flat image: pixel centres equally spaced in tan(angle)
// (a raster projector's image on a plane normal to its axis), so the FOV edges are
// +-fov/2 exactly at the outer pixel edges. The pixel-beam model (A.2.1, Fig. S3) is data
// for the resolution and lens analyses: pixelBeamFwhm() gives the footprint at a throw.

#include <array>
#include <vector>

#include <Eigen/Core>

#include "model/scene/scene.h"

namespace fovea {

// Grid (columns, rows) of about `rays` rays with the FOV's aspect, never finer than the pixels.
std::array<int, 2> projectorGrid(const Projector& p, int rays);

struct ProjectorRay {
  Eigen::Vector3d direction;        // unit, bench frame
  std::array<double, 2> angle_deg;  // horizontal, vertical angle from the projector axis
  std::array<int, 2> pixel;         // column, row of the grid
};

// Source point: the projector position moved by source_shift_mm along bench z (seed A.4: the
// point light source travels along z; its aim is kept).
Eigen::Vector3d projectorSource(const Projector& p, double source_shift_mm);
std::vector<ProjectorRay> projectorRays(const Projector& p, int rays);

// Pixel footprint FWHM at a throw distance (µm): long axis shrinks linearly from the exit
// FWHM to the waist FWHM at waist_distance, then grows linearly with the divergence
// (1 mrad x 1 mm = 1 µm); the long/short ratio relaxes from exit_ellipticity to 1 as
// exp(-throw / waist_distance) (our reading of Fig. S3: elliptical at the exit, round far out).
struct PixelBeamSize {
  double long_axis_um = 0.0;
  double short_axis_um = 0.0;
};
PixelBeamSize pixelBeamFwhm(const PixelBeamModel& m, double throw_mm);

}  // namespace fovea
