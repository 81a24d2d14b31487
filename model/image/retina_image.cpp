#include "model/image/retina_image.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include <tbb/parallel_for.h>
#include <tbb/task_group.h>
#include <opencv2/imgproc.hpp>

#include "model/image/foveation.h"
#include "model/physics/projector_rays.h"
#include "model/physics/trace.h"

namespace fovea::image {

namespace {

int retinaChannelOf(double wavelength_nm) {
  return wavelength_nm >= 590.0 ? 0 : (wavelength_nm >= 490.0 ? 1 : 2);
}

// Bilinear retinaSplat of `power` at canvas coordinates (x, y) (pixel centres at integers).
void retinaSplat(cv::Mat& plane, double x, double y, double power) {
  const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  const double fx = x - x0, fy = y - y0;
  auto add = [&](int xx, int yy, double w) { plane.at<double>(yy, xx) += w * power; };
  add(x0, y0, (1 - fx) * (1 - fy));
  add(x0 + 1, y0, fx * (1 - fy));
  add(x0, y0 + 1, (1 - fx) * fy);
  add(x0 + 1, y0 + 1, fx * fy);
}

// Bilinear retinaSample of a CV_32FC3 image at (x, y); zero outside.
cv::Vec3d retinaSample(const cv::Mat& img, double x, double y) {
  if (!(x >= -0.5 && y >= -0.5 && x <= img.cols - 0.5 && y <= img.rows - 0.5)) return {0, 0, 0};
  const double cx = std::clamp(x, 0.0, img.cols - 1.0), cy = std::clamp(y, 0.0, img.rows - 1.0);
  const int x0 = std::min(static_cast<int>(cx), img.cols - 2 < 0 ? 0 : img.cols - 2);
  const int y0 = std::min(static_cast<int>(cy), img.rows - 2 < 0 ? 0 : img.rows - 2);
  const int x1 = std::min(x0 + 1, img.cols - 1), y1 = std::min(y0 + 1, img.rows - 1);
  const double fx = cx - x0, fy = cy - y0;
  const cv::Vec3f& a = img.at<cv::Vec3f>(y0, x0);
  const cv::Vec3f& b = img.at<cv::Vec3f>(y0, x1);
  const cv::Vec3f& c = img.at<cv::Vec3f>(y1, x0);
  const cv::Vec3f& d = img.at<cv::Vec3f>(y1, x1);
  cv::Vec3d out;
  for (int k = 0; k < 3; ++k) out[k] = (1 - fy) * ((1 - fx) * a[k] + fx * b[k]) + fy * ((1 - fx) * c[k] + fx * d[k]);
  return out;
}

// A PSF grid (sample_arcmin per retinaSample, centred) binned into canvas pixels (ppx, ppy per degree),
// cut at the radius holding all but 1e-5 of its power, renormalised.
cv::Mat retinaBinPsf(const cv::Mat& psf, double sample_arcmin, double ppx, double ppy) {
  const double r_keep = encircledEnergyRadiusArcmin(psf, sample_arcmin, 1.0 - 1e-5);
  const int rx = static_cast<int>(std::ceil(r_keep / 60.0 * ppx)) + 1;
  const int ry = static_cast<int>(std::ceil(r_keep / 60.0 * ppy)) + 1;
  cv::Mat k(2 * ry + 1, 2 * rx + 1, CV_64F, cv::Scalar(0));
  const int c = psf.cols / 2, cy = psf.rows / 2;
  for (int y = 0; y < psf.rows; ++y) {
    const double* row = psf.ptr<double>(y);
    for (int x = 0; x < psf.cols; ++x) {
      const double ax = (x - c) * sample_arcmin / 60.0 * ppx, ay = (y - cy) * sample_arcmin / 60.0 * ppy;
      const int bx = static_cast<int>(std::lround(ax)) + rx, by = static_cast<int>(std::lround(ay)) + ry;
      if (bx >= 0 && by >= 0 && bx < k.cols && by < k.rows) k.at<double>(by, bx) += row[x];
    }
  }
  k /= cv::sum(k)[0];
  return k;
}

// Gaussian blur of a power plane (zero outside), sigma in pixels, power conserved. A wide
// kernel runs on a k-times sum-pooled copy (sigma/k >= 4 px; pooling adds a k-px box, variance
// k^2/12, under 0.6 % of sigma^2) and is brought back bilinearly, rescaled to the exact power.
cv::Mat retinaGaussianBlur(const cv::Mat& plane, double sx, double sy) {
  if (sx <= 0.05 && sy <= 0.05) return plane.clone();
  const int k = std::max(1, static_cast<int>(std::floor(std::min(sx, sy) / 4.0)));
  auto blur = [](const cv::Mat& in, double gx, double gy) {
    cv::Mat out;
    const int kx = 2 * static_cast<int>(std::ceil(4.0 * gx)) + 1, ky = 2 * static_cast<int>(std::ceil(4.0 * gy)) + 1;
    cv::GaussianBlur(in, out, cv::Size(kx, ky), gx, gy, cv::BORDER_CONSTANT);
    return out;
  };
  if (k == 1) return blur(plane, sx, sy);
  const double power = cv::sum(plane)[0];
  // Block sums straight from the plane (no padded copy), as block means.
  cv::Mat low((plane.rows + k - 1) / k, (plane.cols + k - 1) / k, CV_64F, cv::Scalar(0));
  for (int y = 0; y < plane.rows; ++y) {
    const double* in = plane.ptr<double>(y);
    double* lo = low.ptr<double>(y / k);
    for (int x = 0; x < plane.cols; ++x) lo[x / k] += in[x];
  }
  low *= 1.0 / (static_cast<double>(k) * k);
  low = blur(low, sx / k, sy / k);
  cv::Mat up;
  cv::resize(low, up, cv::Size(low.cols * k, low.rows * k), 0, 0, cv::INTER_LINEAR);
  cv::Mat out = up(cv::Rect(0, 0, plane.cols, plane.rows));  // a view: no copy
  const double now = cv::sum(out)[0];
  if (now > 0) out *= power / now;
  return out;
}

// The pooling factor of a wide Gaussian: k with sigma / k >= 4 px (1 when sigma < 8 px).
int retinaPoolFactor(double sx, double sy) {
  return std::max(1, static_cast<int>(std::floor(std::min(sx, sy) / 4.0)));
}

// A plane splatted bilinearly on the k-times coarser grid, blurred to sigma (full-resolution
// px) and interpolated bilinearly back to `size`, its power kept. The bilinear splat and the
// bilinear interpolation are each a tent of one coarse pixel, variance 1/6 coarse px^2 (a
// point at a uniform sub-pixel offset f: E[f(1-f)] = 1/6); variances of convolved kernels
// add, so the coarse Gaussian takes sigma_c^2 = (sigma/k)^2 - 1/3 and the total is sigma^2.
cv::Mat retinaCoarseBlur(const cv::Mat& coarse, double sx, double sy, int k, cv::Size size) {
  const double power = cv::sum(coarse)[0];
  const double gx = std::sqrt(std::max(0.0, sx * sx / (k * k) - 1.0 / 3.0));
  const double gy = std::sqrt(std::max(0.0, sy * sy / (k * k) - 1.0 / 3.0));
  cv::Mat low;
  cv::GaussianBlur(
      coarse, low,
      cv::Size(2 * static_cast<int>(std::ceil(4.0 * gx)) + 1, 2 * static_cast<int>(std::ceil(4.0 * gy)) + 1), gx, gy,
      cv::BORDER_CONSTANT);
  cv::Mat up;
  cv::resize(low, up, cv::Size(low.cols * k, low.rows * k), 0, 0, cv::INTER_LINEAR);
  cv::Mat out = up(cv::Rect(0, 0, size.width, size.height));  // a view: no copy
  const double now = cv::sum(out)[0];
  if (now > 0) out *= power / now;
  return out;
}

}  // namespace

cv::Mat speckleField(cv::Size size, int patterns, std::uint64_t seed) {
  if (patterns < 1) throw std::invalid_argument("speckle: patterns must be >= 1");
  std::mt19937_64 rng(seed);
  std::exponential_distribution<double> expo(1.0);  // |complex circular Gaussian|^2, mean 1
  cv::Mat f(size, CV_64F, cv::Scalar(0));
  for (int y = 0; y < size.height; ++y) {
    double* row = f.ptr<double>(y);
    for (int x = 0; x < size.width; ++x) {
      double s = 0;
      for (int p = 0; p < patterns; ++p) s += expo(rng);
      row[x] = s / patterns;
    }
  }
  return f;
}

double speckleContrast(const cv::Mat& field, const cv::Mat& mask) {
  cv::Scalar mean, sd;
  cv::meanStdDev(field, mean, sd, mask);
  return mean[0] > 0 ? sd[0] / mean[0] : 0.0;
}

RetinaImageResult renderRetinaImage(const Scene& scene, const cv::Mat& target, const RetinaImageOptions& o) {
  if (target.empty() || target.type() != CV_32FC3) throw std::invalid_argument("retina image: target must be CV_32FC3");
  if (!std::isfinite(o.accommodation_d) || o.accommodation_d < 0 || o.accommodation_d > 10)
    throw std::invalid_argument("accommodation must be within 0..10 D");
  RetinaImageResult r;
  const DisplayAngles ang = displayAngles(scene);
  const double ppx = target.cols / ang.peripheral_fov_deg[0], ppy = target.rows / ang.peripheral_fov_deg[1];
  r.pixels_per_degree = ppx;

  // Line-of-sight PSFs.
  const auto& lasers = scene.projector.wavelengths_nm;
  for (double wl : lasers)
    r.peripheral.push_back(peripheralSpot(scene, wl, o.accommodation_d, o.gaze_deg, o.hoe_shift_mm));
  // The foveal PSFs (Fourier optics, the expensive part) and the preview's two display images
  // are independent: computed concurrently (TBB; the eye's part of each PSF is cached across
  // gazes, retinal_psf.cpp).
  const auto& primaries = scene.foveal_display.primaries_nm;
  r.foveal.resize(primaries.size());
  std::vector<cv::Mat> fkernels(primaries.size());
  FoveatedCompositor comp(scene, o.blend);
  tbb::task_group concurrent;
  concurrent.run([&] {
    tbb::parallel_for(std::size_t{0}, primaries.size(), [&](std::size_t i) {
      r.foveal[i] = fovealSpot(scene, primaries[i], o.accommodation_d, o.gaze_deg);
      fkernels[i] = retinaBinPsf(r.foveal[i].psf, r.foveal[i].sample_arcmin, ppx, ppy);
    });
  });
  concurrent.run([&] {
    comp.setTarget(target);
    comp.update(o.gaze_deg);
  });
  concurrent.wait();
  auto nearest555 = [](auto getter, std::size_t n) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < n; ++i)
      if (std::abs(getter(i) - 555.0) < std::abs(getter(best) - 555.0)) best = i;
    return best;
  };
  r.peripheral_reference = nearest555([&](std::size_t i) { return lasers[i]; }, lasers.size());
  r.foveal_reference = nearest555([&](std::size_t i) { return scene.foveal_display.primaries_nm[i]; },
                                  scene.foveal_display.primaries_nm.size());

  // Peripheral kernels: sigma = w/2 (1/e^2 radius w) in canvas pixels; a spot whose line of
  // sight misses the plate takes the largest valid one (or none).
  double w_fallback = 0;
  for (const auto& s : r.peripheral)
    if (s.valid) w_fallback = std::max(w_fallback, s.radius_1e2_arcmin);
  std::vector<std::array<double, 2>> sig(lasers.size());
  int margin = 4;
  for (std::size_t i = 0; i < lasers.size(); ++i) {
    const double w = r.peripheral[i].valid ? r.peripheral[i].radius_1e2_arcmin : w_fallback;
    sig[i] = {0.5 * w / 60.0 * ppx, 0.5 * w / 60.0 * ppy};
    margin = std::max(margin, static_cast<int>(std::ceil(4.0 * std::max(sig[i][0], sig[i][1]))) + 2);
  }
  for (const auto& k : fkernels) margin = std::max(margin, std::max(k.cols, k.rows) / 2 + 2);
  // Cells at the field's edge spread up to 64 px beyond it; kernels need `margin` more.
  const int kernel_margin = margin;
  margin += 64;
  r.margin_px = margin;
  const cv::Size canvas_size(target.cols + 2 * margin, target.rows + 2 * margin);
  auto cx = [&](double yaw) { return (yaw / ang.peripheral_fov_deg[0] + 0.5) * target.cols - 0.5 + margin; };
  auto cy = [&](double pitch) { return (0.5 - pitch / ang.peripheral_fov_deg[1]) * target.rows - 0.5 + margin; };
  auto inside = [&](double x, double y) {
    return x >= kernel_margin && y >= kernel_margin && x < canvas_size.width - 1 - kernel_margin &&
           y < canvas_size.height - 1 - kernel_margin;
  };

  const cv::Mat& periph = comp.peripheralImage();

  // Peripheral: trace, per laser plane.
  TraceOptions to;
  to.gaze_deg = o.gaze_deg;
  to.hoe_shift_mm = o.hoe_shift_mm;
  to.rays = o.rays;
  to.keep_rays = true;
  const TraceResult tr = traceScene(scene, to);
  const auto grid = projectorGrid(scene.projector, o.rays);
  const int nx = grid[0], ny = grid[1];
  // The calibration laser's landing angle per projector pixel (B.2.1: one geometric mapping
  // for all colours): the content each pixel shows. Any of its rays that leaves the plate
  // towards the eye counts (a fitted calibration extrapolates past the camera's pupil); a
  // pixel without one falls back to each laser's own angle.
  const std::size_t calib = calibrationLaser(lasers);
  std::vector<std::optional<std::array<double, 2>>> calib_field(static_cast<std::size_t>(nx) * ny);
  if (!o.per_laser_calibration && !lasers.empty())
    for (const auto& ray : tr.ray_list)
      if (ray.wavelength_nm == lasers[calib] && ray.exits && ray.towards_eye) {
        const auto idx = static_cast<std::size_t>(ray.pixel[1]) * nx + ray.pixel[0];
        if (idx < calib_field.size()) calib_field[idx] = ray.field_deg;
      }
  r.lateral_colour = lateralColourAtLineOfSight(scene, o.gaze_deg, o.hoe_shift_mm);
  std::array<int, 3> lasers_in_channel{0, 0, 0};
  for (double wl : lasers) ++lasers_in_channel[static_cast<std::size_t>(retinaChannelOf(wl))];
  // Foveal: the micro-OLED's pixels at gaze + their equal-angle offsets, on the canvas region
  // they reach (their field plus the widest kernel; zero elsewhere, so nothing is lost); one
  // task per channel, run alongside the lasers' tasks.
  const cv::Mat& fov = comp.fovealImage();
  const double fw = ang.foveal_fov_deg[0] / fov.cols, fh = ang.foveal_fov_deg[1] / fov.rows;
  const double parea = fw * fh * ppx * ppy;
  int kernel_half = 0;
  for (const auto& k : fkernels) kernel_half = std::max(kernel_half, std::max(k.cols, k.rows) / 2);
  const int x_lo = static_cast<int>(std::floor(cx(o.gaze_deg[0] - 0.5 * ang.foveal_fov_deg[0]))) - kernel_half - 2;
  const int x_hi = static_cast<int>(std::ceil(cx(o.gaze_deg[0] + 0.5 * ang.foveal_fov_deg[0]))) + kernel_half + 3;
  const int y_lo = static_cast<int>(std::floor(cy(o.gaze_deg[1] + 0.5 * ang.foveal_fov_deg[1]))) - kernel_half - 2;
  const int y_hi = static_cast<int>(std::ceil(cy(o.gaze_deg[1] - 0.5 * ang.foveal_fov_deg[1]))) + kernel_half + 3;
  const cv::Rect froi = cv::Rect(x_lo, y_lo, x_hi - x_lo, y_hi - y_lo) & cv::Rect(cv::Point(0, 0), canvas_size);
  // Channel k takes the PSF of the primary in its band (else the primary nearest 555 nm). The
  // pupil PSF is centro-symmetric, so filter2D's correlation is the convolution.
  std::array<double, 3> fdeposited{0, 0, 0};
  std::array<cv::Mat, 3> fblurred;
  auto foveal_work = [&] {
    if (fkernels.empty() || froi.area() == 0) return;
    tbb::parallel_for(0, 3, [&](int k) {
      cv::Mat plane(froi.size(), CV_64F, cv::Scalar(0));
      for (int v = 0; v < fov.rows; ++v) {
        const double pitch = o.gaze_deg[1] + (0.5 - (v + 0.5) / fov.rows) * ang.foveal_fov_deg[1];
        const auto* row = fov.ptr<cv::Vec3f>(v);
        for (int u = 0; u < fov.cols; ++u) {
          const double power = row[u][k] * parea;
          if (power == 0) continue;
          const double yaw = o.gaze_deg[0] + ((u + 0.5) / fov.cols - 0.5) * ang.foveal_fov_deg[0];
          const double x = cx(yaw), y = cy(pitch);
          if (!inside(x, y)) continue;
          retinaSplat(plane, x - froi.x, y - froi.y, power);
          fdeposited[static_cast<std::size_t>(k)] += power;
        }
      }
      std::size_t kernel = r.foveal_reference;
      for (std::size_t i = 0; i < primaries.size(); ++i)
        if (retinaChannelOf(primaries[i]) == k) kernel = i;
      cv::filter2D(plane, fblurred[static_cast<std::size_t>(k)], CV_64F, fkernels[kernel], cv::Point(-1, -1), 0,
                   cv::BORDER_CONSTANT);
    });
  };

  // Each laser's plane is splatted and blurred on its own (TBB, one task per laser).
  std::vector<cv::Mat> planes(lasers.size()), blurred_planes(lasers.size());
  std::vector<double> deposited_per(lasers.size(), 0.0), lost_per(lasers.size(), 0.0);
  std::vector<int> in_pupil_per(lasers.size(), 0);
  tbb::task_group displays;
  displays.run(foveal_work);
  tbb::parallel_for(std::size_t{0}, lasers.size(), [&](std::size_t li) {
    double& deposited = deposited_per[li];
    double& lost = lost_per[li];
    // A wide PSF (sigma >= 8 px) without speckle: the cells are splatted straight onto a
    // k-times coarser grid (retinaPoolFactor), blurred there and brought back.
    const int kpool = o.speckle_patterns > 0 ? 1 : retinaPoolFactor(sig[li][0], sig[li][1]);
    const double pool_inv = 1.0 / kpool, pool_off = 0.5 * (kpool - 1);  // coarse pixel j centres at j k + (k-1)/2
    cv::Mat plane(kpool > 1
                      ? cv::Size((canvas_size.width + kpool - 1) / kpool, (canvas_size.height + kpool - 1) / kpool)
                      : canvas_size,
                  CV_64F, cv::Scalar(0));
    // The rays of this laser on their grid.
    std::vector<const TracedRay*> cell(static_cast<std::size_t>(nx) * ny, nullptr);
    for (const auto& ray : tr.ray_list)
      if (ray.wavelength_nm == lasers[li] && ray.in_pupil && ray.exits && ray.towards_eye) {
        const auto idx = static_cast<std::size_t>(ray.pixel[1]) * nx + ray.pixel[0];
        if (idx < cell.size()) cell[idx] = &ray;
      }
    auto at = [&](int ix, int iy) -> const TracedRay* {
      return ix < 0 || iy < 0 || ix >= nx || iy >= ny ? nullptr : cell[static_cast<std::size_t>(iy) * nx + ix];
    };
    // Field-angle area of each cell: |det J| from central (or one-sided) differences; J's
    // columns (du, dv: the cell's edges in the visual field) also shape its splat.
    std::vector<double> areas(cell.size(), 0.0);
    std::vector<std::array<double, 4>> edges(cell.size(), {0, 0, 0, 0});
    std::vector<double> known;
    for (int iy = 0; iy < ny; ++iy)
      for (int ix = 0; ix < nx; ++ix) {
        const TracedRay* c = at(ix, iy);
        if (!c) continue;
        auto diff = [&](int dx, int dy) -> std::optional<std::array<double, 2>> {
          const TracedRay* p = at(ix + dx, iy + dy);
          const TracedRay* m = at(ix - dx, iy - dy);
          if (p && m)
            return std::array<double, 2>{0.5 * (p->field_deg[0] - m->field_deg[0]),
                                         0.5 * (p->field_deg[1] - m->field_deg[1])};
          if (p) return std::array<double, 2>{p->field_deg[0] - c->field_deg[0], p->field_deg[1] - c->field_deg[1]};
          if (m) return std::array<double, 2>{c->field_deg[0] - m->field_deg[0], c->field_deg[1] - m->field_deg[1]};
          return std::nullopt;
        };
        const auto du = diff(1, 0), dv = diff(0, 1);
        if (du && dv) {
          const double a = std::abs((*du)[0] * (*dv)[1] - (*du)[1] * (*dv)[0]);
          areas[static_cast<std::size_t>(iy) * nx + ix] = a;
          edges[static_cast<std::size_t>(iy) * nx + ix] = {(*du)[0], (*du)[1], (*dv)[0], (*dv)[1]};
          known.push_back(a);
        }
      }
    double median_area = 0;
    if (!known.empty()) {
      std::nth_element(known.begin(), known.begin() + static_cast<std::ptrdiff_t>(known.size() / 2), known.end());
      median_area = known[known.size() / 2];
    }
    const int ch = retinaChannelOf(lasers[li]);
    const double share = 1.0 / lasers_in_channel[static_cast<std::size_t>(ch)];
    for (std::size_t k = 0; k < cell.size(); ++k) {
      const TracedRay* c = cell[k];
      if (!c) continue;
      ++in_pupil_per[li];
      const double yaw = o.gaze_deg[0] + c->field_deg[0], pitch = o.gaze_deg[1] + c->field_deg[1];
      const double x = cx(yaw), y = cy(pitch);
      if (!inside(x, y)) continue;  // outside the target field: the projector shows black there
      // The content this pixel shows: at the calibration laser's landing angle (its own
      // angle with per-laser calibration).
      const auto& cf = calib_field[k];
      const double show_yaw = cf ? o.gaze_deg[0] + (*cf)[0] : yaw, show_pitch = cf ? o.gaze_deg[1] + (*cf)[1] : pitch;
      const cv::Vec3d v = retinaSample(periph, (show_yaw / ang.peripheral_fov_deg[0] + 0.5) * periph.cols - 0.5,
                                       (0.5 - show_pitch / ang.peripheral_fov_deg[1]) * periph.rows - 0.5);
      const double area = (areas[k] > 0 ? areas[k] : median_area) * ppx * ppy;
      const double power = share * v[ch] * c->efficiency * area;
      if (power == 0) continue;
      // The ray stands for its cell of projector pixels: its power is spread evenly over the
      // cell's parallelogram in the visual field (Kx x Ky bilinear sub-splats, about one per
      // canvas pixel), so a ray grid coarser than the PSF leaves no ripple.
      const auto& ed = edges[k];
      const double ux = ed[0] * ppx, uy = -ed[1] * ppy, vx = ed[2] * ppx, vy = -ed[3] * ppy;
      const int kx = std::clamp(static_cast<int>(std::ceil(std::hypot(ux, uy) * pool_inv)), 1, 64);
      const int ky = std::clamp(static_cast<int>(std::ceil(std::hypot(vx, vy) * pool_inv)), 1, 64);
      const double sub = power / (kx * ky);
      for (int j = 0; j < ky; ++j)
        for (int i = 0; i < kx; ++i) {
          const double fu = (i + 0.5) / kx - 0.5, fv = (j + 0.5) / ky - 0.5;
          const double sx = x + fu * ux + fv * vx, sy = y + fu * uy + fv * vy;
          if (inside(sx, sy)) {
            retinaSplat(plane, (sx - pool_off) * pool_inv, (sy - pool_off) * pool_inv, sub);
            deposited += sub;
          } else {
            lost += sub;
          }
        }
    }
    blurred_planes[li] = kpool > 1 ? retinaCoarseBlur(plane, sig[li][0], sig[li][1], kpool, canvas_size)
                                   : retinaGaussianBlur(plane, sig[li][0], sig[li][1]);
    if (o.speckle_patterns > 0) planes[li] = std::move(plane);  // its lit mask
  });
  displays.wait();
  double deposited = 0, lost = 0;
  for (std::size_t li = 0; li < lasers.size(); ++li) {
    deposited += deposited_per[li];
    lost += lost_per[li];
    r.rays_in_pupil += in_pupil_per[li];
  }
  r.rays_traced = tr.rays;

  // Peripheral PSFs (and speckle), per laser, into the channels.
  std::vector<cv::Mat> channels(3);  // a channel's first laser plane is moved in, later ones added
  cv::Mat speckle_sum = o.speckle_patterns > 0 ? cv::Mat(canvas_size, CV_64F, cv::Scalar(0)) : cv::Mat(), lit;
  for (std::size_t li = 0; li < planes.size(); ++li) {
    cv::Mat blurred = std::move(blurred_planes[li]);
    if (o.speckle_patterns > 0) {
      const cv::Mat s = speckleField(canvas_size, o.speckle_patterns, o.speckle_seed + 7919 * li);
      const double before = cv::sum(blurred)[0];
      cv::Mat sp = blurred.mul(s);
      const double after = cv::sum(sp)[0];
      if (after > 0) sp *= before / after;
      blurred = sp;
      speckle_sum += s;
    }
    cv::Mat& channel = channels[static_cast<std::size_t>(retinaChannelOf(lasers[li]))];
    if (channel.empty())
      channel = std::move(blurred);
    else
      channel += blurred;
  }
  for (auto& c : channels)
    if (c.empty()) c = cv::Mat(canvas_size, CV_64F, cv::Scalar(0));
  if (o.speckle_patterns > 0 && !lasers.empty()) {
    speckle_sum /= static_cast<double>(lasers.size());
    cv::Mat any = planes[0].clone();
    for (std::size_t li = 1; li < planes.size(); ++li) any += planes[li];
    lit = any > 0;
    r.speckle_contrast = speckleContrast(speckle_sum, lit);
    r.speckle_expected = 1.0 / std::sqrt(static_cast<double>(o.speckle_patterns) * lasers.size());
  }

  for (int k = 0; k < 3; ++k)
    if (!fblurred[static_cast<std::size_t>(k)].empty()) {
      cv::Mat dst = channels[static_cast<std::size_t>(k)](froi);
      dst += fblurred[static_cast<std::size_t>(k)];
    }
  deposited += fdeposited[0] + fdeposited[1] + fdeposited[2];

  cv::merge(channels, r.canvas);
  r.power_in_pupil = deposited + lost;
  r.power_off_canvas = lost;
  const cv::Scalar tot = cv::sum(r.canvas);
  r.power_on_retina = tot[0] + tot[1] + tot[2];
  r.canvas(cv::Rect(margin, margin, target.cols, target.rows)).convertTo(r.image, CV_32FC3);
  return r;
}

}  // namespace fovea::image
