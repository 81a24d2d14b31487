#pragma once
// Speckle grain on the retina (issue 29), an option of the retinal image.
//
// Stated model. Laser light scattered on its way (the HOE's film and its sealing: haze) and
// collected by the eye forms subjective speckle on the retina: a circular complex Gaussian
// field, fully developed (the intensity of one pattern exponential with mean 1; Goodman,
// "Speckle Phenomena in Optics", Roberts 2007, ch. 3), whose angular spectrum fills the pupil
// (the scattered light crosses the whole pupil, whatever the Maxwellian beam's own size). The
// intensity's correlation over visual angle is then |mu(theta)|^2 = [2 J1(v)/v]^2,
// v = pi D theta / lambda (the pupil's Airy pattern; Goodman, ch. 4), of correlation solid
// angle Omega_c = integral |mu|^2 = 4 lambda^2 / (pi D^2), about (0.4 arcmin)^2 at 550 nm and
// 5 mm: far under a canvas pixel of the 1080p retinal image (1.25 arcmin).
// A canvas pixel (a x b of visual angle) integrates the speckle: its value has M degrees of
// freedom,
//     1/M = (1 / (a b)^2) integral integral (a - |dx|)(b - |dy|) |mu(dx, dy)|^2 ddx ddy
// (Goodman, ch. 4, integrated speckle), M -> 1 for a pixel much smaller than the grain and
// M -> a b / Omega_c for a much larger one, and is taken gamma-distributed with M degrees of
// freedom (Goodman's approximation of integrated speckle): contrast 1/sqrt(M). N independent
// patterns (wavelengths, diffusers, frames) add degrees of freedom: contrast 1/sqrt(M N).
// Neighbouring pixels are taken independent (exact for a grain under a pixel: they share
// only the grains on their border).
//
// Units: angles in arcmin, wavelength in nm, pupil in mm.

#include <cstdint>

#include <opencv2/core.hpp>

namespace fovea::image {

// M of a pixel a x b arcmin for speckle through a pupil of diameter D at lambda (above).
double speckleDegreesOfFreedom(double pixel_w_arcmin, double pixel_h_arcmin, double wavelength_nm,
                               double pupil_diameter_mm);

// Correlation solid angle Omega_c = 4 lambda^2 / (pi D^2), as arcmin^2.
double speckleCorrelationAreaArcmin2(double wavelength_nm, double pupil_diameter_mm);

// A field of unit-mean gamma values with `dof` degrees of freedom (contrast 1/sqrt(dof)),
// CV_64F; dof = M x patterns.
cv::Mat integratedSpeckleField(cv::Size size, double dof, std::uint64_t seed);

}  // namespace fovea::image
