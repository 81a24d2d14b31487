#include "model/analysis/accommodation_resolution.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace fovea {

namespace {

std::size_t accommodationNearest555(const std::vector<double>& wavelengths_nm) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < wavelengths_nm.size(); ++i)
    if (std::abs(wavelengths_nm[i] - 555.0) < std::abs(wavelengths_nm[best] - 555.0)) best = i;
  return best;
}

// (max - min) / min over the positive values; nothing with fewer than two.
std::optional<double> accommodationRelativeChange(const std::vector<double>& v) {
  if (v.size() < 2) return std::nullopt;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  if (!(*lo > 0)) return std::nullopt;
  return (*hi - *lo) / *lo;
}

}  // namespace

AccommodationList parseAccommodationList(const std::string& text) {
  AccommodationList out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const auto first = item.find_first_not_of(" \t");
    const auto last = item.find_last_not_of(" \t");
    const std::string t = first == std::string::npos ? std::string() : item.substr(first, last - first + 1);
    char* end = nullptr;
    const double x = std::strtod(t.c_str(), &end);
    if (t.empty() || end != t.c_str() + t.size()) {
      out.problem = "'" + t + "' is not a number (a comma list of diopters: 0.4,1,3.3)";
      return out;
    }
    if (!std::isfinite(x) || x < kAccommodationMinD || x > kAccommodationMaxD) {
      std::ostringstream os;
      os << "each accommodation must lie in [" << kAccommodationMinD << ", " << kAccommodationMaxD << "] D, got '" << t
         << "'";
      out.problem = os.str();
      return out;
    }
    out.values_d.push_back(x);
  }
  if (!text.empty() && text.back() == ',') out.problem = "a trailing comma: the list ends with an empty value";
  if (out.values_d.empty() && !out.problem) out.problem = "no accommodation given";
  if (out.values_d.size() > kMaxAccommodationSamples)
    out.problem = "at most " + std::to_string(kMaxAccommodationSamples) + " accommodations";
  return out;
}

AccommodationResolution resolutionVsAccommodation(const Scene& scene, std::array<double, 2> gaze_deg,
                                                  const std::vector<double>& accommodations_d) {
  AccommodationResolution r;
  r.gaze_deg = gaze_deg;
  r.peripheral_reference = accommodationNearest555(scene.projector.wavelengths_nm);
  r.foveal_reference = accommodationNearest555(scene.foveal_display.primaries_nm);
  std::vector<double> pspots, fspots;
  for (double a : accommodations_d) {
    AccommodationSample s;
    s.accommodation_d = a;
    for (double wl : scene.projector.wavelengths_nm) s.peripheral.push_back(peripheralSpot(scene, wl, a, gaze_deg));
    for (double wl : scene.foveal_display.primaries_nm) {
      FovealSpot f = fovealSpot(scene, wl, a, gaze_deg);
      f.psf.release();  // the grid is the image's business, not the sweep's
      s.foveal.push_back(std::move(f));
    }
    if (r.peripheral_reference < s.peripheral.size() && s.peripheral[r.peripheral_reference].valid)
      pspots.push_back(s.peripheral[r.peripheral_reference].metrics.fwhm_arcmin);
    if (r.foveal_reference < s.foveal.size()) fspots.push_back(s.foveal[r.foveal_reference].metrics.fwhm_arcmin);
    r.samples.push_back(std::move(s));
  }
  r.peripheral_spot_change = accommodationRelativeChange(pspots);
  r.foveal_spot_change = accommodationRelativeChange(fspots);
  return r;
}

}  // namespace fovea
