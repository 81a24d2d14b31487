#pragma once
// Colours of diffraction efficiency shared by the 3D view, the efficiency map, the grating
// vector cloud and the retina view: a perceptual purple -> magenta -> orange -> yellow ramp
// over [kLowEfficiency, 1]; below kLowEfficiency (the FOV threshold of the trace, Fig. S5)
// everything is gray.

#include <array>

#include <vtkSmartPointer.h>

class vtkLookupTable;
class vtkScalarBarActor;

namespace fovea::viz {

inline constexpr double kLowEfficiency = 0.1;
inline constexpr std::array<double, 3> kLowEfficiencyGray{0.50, 0.50, 0.52};

// RGB in 0..1 of an efficiency (clamped to [0, 1]).
std::array<double, 3> efficiencyColor(double efficiency);

// 256 colours over [kLowEfficiency, 1], below-range colour gray.
vtkSmartPointer<vtkLookupTable> efficiencyLookupTable();

// A vertical colour bar of efficiencyLookupTable() titled "efficiency", with a "< 0.1" gray
// swatch, at the right edge of its renderer.
vtkSmartPointer<vtkScalarBarActor> efficiencyColorBar();

}  // namespace fovea::viz
