#include "model/image/retina_image.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include <tbb/parallel_for.h>
#include <tbb/task_group.h>
#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "model/image/foveation.h"
#include "model/image/speckle_grain.h"
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

// The pooling factor of a wide Gaussian: k with sigma / k >= 4 px (1 when sigma < 8 px).
int retinaPoolFactor(double sx, double sy) {
  return std::max(1, static_cast<int>(std::floor(std::min(sx, sy) / 4.0)));
}

// A sampled elliptical Gaussian of covariance `cov` (px^2, x right, y down), sum 1, cut at 4
// sigma. Eigenvalues under (0.2 px)^2 are raised to it (a point at that scale).
cv::Mat ellipticalGaussianKernel(Eigen::Matrix2d cov) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(0.5 * (cov + cov.transpose()));
  Eigen::Vector2d ev = es.eigenvalues().cwiseMax(0.04);
  cov = es.eigenvectors() * ev.asDiagonal() * es.eigenvectors().transpose();
  const int rx = static_cast<int>(std::ceil(4.0 * std::sqrt(cov(0, 0))));
  const int ry = static_cast<int>(std::ceil(4.0 * std::sqrt(cov(1, 1))));
  const Eigen::Matrix2d inv = cov.inverse();
  cv::Mat k(2 * ry + 1, 2 * rx + 1, CV_64F);
  for (int y = -ry; y <= ry; ++y)
    for (int x = -rx; x <= rx; ++x)
      k.at<double>(y + ry, x + rx) = std::exp(-0.5 * (inv(0, 0) * x * x + 2 * inv(0, 1) * x * y + inv(1, 1) * y * y));
  k /= cv::sum(k)[0];
  return k;
}

// The nodes of the field-dependent PSF over the target field (world yaw, pitch; deg), about
// 10 deg apart, at least two per axis, and the bilinear weights of a point among them
// (coordinates clamped to the grid: weights sum to 1 everywhere).
struct ZoneGrid {
  int nx = 2, ny = 2;
  double yaw0 = 0, pitch0 = 0, dyaw = 1, dpitch = 1;
  double yaw(int i) const { return yaw0 + i * dyaw; }
  double pitch(int j) const { return pitch0 + j * dpitch; }
  std::array<double, 2> node(std::size_t z) const {
    return {yaw(static_cast<int>(z % static_cast<std::size_t>(nx))), pitch(static_cast<int>(z / nx))};
  }
  std::array<std::pair<std::size_t, double>, 4> weights(double yaw_deg, double pitch_deg) const {
    const double fx = std::clamp((yaw_deg - yaw0) / dyaw, 0.0, nx - 1.0);
    const double fy = std::clamp((pitch_deg - pitch0) / dpitch, 0.0, ny - 1.0);
    const int i = std::min(static_cast<int>(fx), nx - 2), j = std::min(static_cast<int>(fy), ny - 2);
    const double tx = fx - i, ty = fy - j;
    auto at = [&](int a, int b) { return static_cast<std::size_t>(b) * nx + a; };
    return {{{at(i, j), (1 - tx) * (1 - ty)},
             {at(i + 1, j), tx * (1 - ty)},
             {at(i, j + 1), (1 - tx) * ty},
             {at(i + 1, j + 1), tx * ty}}};
  }
};
ZoneGrid makeZoneGrid(const std::array<double, 2>& fov_deg) {
  ZoneGrid g;
  g.nx = std::max(2, static_cast<int>(std::lround(fov_deg[0] / 10.0)) + 1);
  g.ny = std::max(2, static_cast<int>(std::lround(fov_deg[1] / 10.0)) + 1);
  g.yaw0 = -0.5 * fov_deg[0];
  g.pitch0 = -0.5 * fov_deg[1];
  g.dyaw = fov_deg[0] / (g.nx - 1);
  g.dpitch = fov_deg[1] / (g.ny - 1);
  return g;
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

  // Peripheral: trace (per laser).
  TraceOptions to;
  to.gaze_deg = o.gaze_deg;
  to.hoe_shift_mm = o.hoe_shift_mm;
  to.rays = o.rays;
  to.keep_rays = true;
  const TraceResult tr = traceScene(scene, to);
  const auto grid = projectorGrid(scene.projector, o.rays);
  const int nx = grid[0], ny = grid[1];

  // Field-dependent peripheral PSFs: the spot (retinal_psf.h, peripheralSpotAt: the HOE's power
  // and astigmatism where the ray meets it) at the nodes of a grid over the target field,
  // about 10 deg apart, from each laser's traced ray landing nearest the node. Between nodes
  // the PSF is interpolated by splitting each ray's power among its four nodes with bilinear
  // weights (a partition of unity) and blurring each node's plane by its own kernel
  // (piecewise-interpolated space-variant blur: Nagy & O'Leary, SIAM J. Sci. Comput. 19, 1063,
  // 1998). A node takes the nearest ray however far it lands (light near the node, if any, is
  // that ray's); a laser with no ray in the pupil takes its line-of-sight spot.
  const ZoneGrid zg = makeZoneGrid(ang.peripheral_fov_deg);
  const std::size_t n_zones = static_cast<std::size_t>(zg.nx) * zg.ny;
  std::vector<std::vector<Eigen::Matrix2d>> zone_cov(lasers.size(), std::vector<Eigen::Matrix2d>(n_zones));
  {
    std::vector<std::vector<const TracedRay*>> nearest(lasers.size(), std::vector<const TracedRay*>(n_zones, nullptr));
    std::vector<std::vector<double>> best_d(lasers.size(), std::vector<double>(n_zones, 1e300));
    for (const auto& ray : tr.ray_list) {
      if (!(ray.in_pupil && ray.exits && ray.towards_eye)) continue;
      const auto it = std::find(lasers.begin(), lasers.end(), ray.wavelength_nm);
      if (it == lasers.end()) continue;
      const auto li = static_cast<std::size_t>(it - lasers.begin());
      const double yaw = o.gaze_deg[0] + ray.field_deg[0], pitch = o.gaze_deg[1] + ray.field_deg[1];
      for (std::size_t z = 0; z < n_zones; ++z) {
        const auto node = zg.node(z);
        const double d = std::hypot(yaw - node[0], pitch - node[1]);
        if (d < best_d[li][z]) {
          best_d[li][z] = d;
          nearest[li][z] = &ray;
        }
      }
    }
    r.peripheral_field.resize(lasers.size() * n_zones);
    tbb::parallel_for(std::size_t{0}, r.peripheral_field.size(), [&](std::size_t j) {
      const std::size_t li = j / n_zones, z = j % n_zones;
      PeripheralSpot sp;
      if (nearest[li][z])
        sp = peripheralSpotAt(scene, lasers[li], o.accommodation_d, o.gaze_deg, o.hoe_shift_mm,
                              nearest[li][z]->hoe_point);
      if (!sp.valid) sp = r.peripheral[li];
      r.peripheral_field[j] = {zg.node(z), sp};
    });
  }
  // A spot whose line of sight misses the plate, and no ray near a node: the largest valid one.
  double w_fallback = 0;
  for (const auto& s : r.peripheral)
    if (s.valid) w_fallback = std::max(w_fallback, s.radius_1e2_arcmin);
  int margin = 4;
  std::vector<double> min_sigma(lasers.size(), 1e300);
  for (std::size_t j = 0; j < r.peripheral_field.size(); ++j) {
    const PeripheralSpot& sp = r.peripheral_field[j].spot;
    Eigen::Matrix2d c;  // canvas px^2: x = yaw, y = -pitch
    if (sp.valid) {
      const double kx = ppx / 60.0, ky = ppy / 60.0;
      c << sp.covariance_arcmin2[0] * kx * kx, -sp.covariance_arcmin2[2] * kx * ky, -sp.covariance_arcmin2[2] * kx * ky,
          sp.covariance_arcmin2[1] * ky * ky;
    } else {
      const double sx = 0.5 * w_fallback / 60.0 * ppx, sy = 0.5 * w_fallback / 60.0 * ppy;
      c << sx * sx, 0, 0, sy * sy;
    }
    zone_cov[j / n_zones][j % n_zones] = c;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(c);
    min_sigma[j / n_zones] = std::min(min_sigma[j / n_zones], std::sqrt(std::max(0.0, es.eigenvalues()[0])));
    margin = std::max(margin, static_cast<int>(std::ceil(4.0 * std::sqrt(std::max(c(0, 0), c(1, 1))))) + 2);
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
  std::vector<cv::Mat> blurred_planes(lasers.size());
  std::vector<double> deposited_per(lasers.size(), 0.0), lost_per(lasers.size(), 0.0);
  std::vector<int> in_pupil_per(lasers.size(), 0);
  tbb::task_group displays;
  displays.run(foveal_work);
  tbb::parallel_for(std::size_t{0}, lasers.size(), [&](std::size_t li) {
    double& deposited = deposited_per[li];
    double& lost = lost_per[li];
    // A wide PSF (sigma >= 8 px everywhere): the cells are splatted straight onto a k-times
    // coarser grid (retinaPoolFactor), blurred there and brought back.
    const int kpool = retinaPoolFactor(min_sigma[li], min_sigma[li]);
    const double pool_inv = 1.0 / kpool, pool_off = 0.5 * (kpool - 1);  // coarse pixel j centres at j k + (k-1)/2
    const cv::Size coarse_size =
        kpool > 1 ? cv::Size((canvas_size.width + kpool - 1) / kpool, (canvas_size.height + kpool - 1) / kpool)
                  : canvas_size;
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
    // Each node's plane covers the canvas between its neighbours (where its weight is not
    // zero), widened by half the largest cell (a cell's splat around its ray) and its kernel.
    double half_cell_px = 0;
    for (const auto& ed : edges)
      half_cell_px =
          std::max(half_cell_px, 0.5 * (std::hypot(ed[0] * ppx, ed[1] * ppy) + std::hypot(ed[2] * ppx, ed[3] * ppy)));
    std::vector<Eigen::Matrix2d> kcov(n_zones);
    std::vector<cv::Rect> zone_rect(n_zones);
    std::vector<cv::Mat> zone_plane(n_zones);
    const double tent = kpool > 1 ? 1.0 / 3.0 : 1.0 / 6.0;  // splat (+ interpolation) tents, coarse px^2
    for (std::size_t z = 0; z < n_zones; ++z) {
      kcov[z] = zone_cov[li][z] / (static_cast<double>(kpool) * kpool) - tent * Eigen::Matrix2d::Identity();
      const int kr = static_cast<int>(std::ceil(4.0 * std::sqrt(std::max({kcov[z](0, 0), kcov[z](1, 1), 0.0}))));
      const int iz = static_cast<int>(z % static_cast<std::size_t>(zg.nx)), jz = static_cast<int>(z / zg.nx);
      const double x0 = iz == 0 ? 0.0 : cx(zg.yaw(iz - 1)),
                   x1 = iz + 1 >= zg.nx ? canvas_size.width : cx(zg.yaw(iz + 1));
      const double y0 = jz + 1 >= zg.ny ? 0.0 : cy(zg.pitch(jz + 1)),
                   y1 = jz == 0 ? canvas_size.height : cy(zg.pitch(jz - 1));
      const double pad = (half_cell_px + 2) * pool_inv + kr + 3;
      const cv::Rect rect(cv::Point(static_cast<int>(std::floor(x0 * pool_inv - pad)),
                                    static_cast<int>(std::floor(y0 * pool_inv - pad))),
                          cv::Point(static_cast<int>(std::ceil(x1 * pool_inv + pad)),
                                    static_cast<int>(std::ceil(y1 * pool_inv + pad))));
      zone_rect[z] = rect & cv::Rect(cv::Point(0, 0), coarse_size);
    }
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
      // The ray's share of each of its (up to) four nodes.
      const auto wz = zg.weights(yaw, pitch);
      for (const auto& [z, w] : wz) {
        if (w <= 0) continue;
        cv::Mat& zp = zone_plane[z];
        if (zp.empty()) zp = cv::Mat(zone_rect[z].size(), CV_64F, cv::Scalar(0));
        const double ox = zone_rect[z].x, oy = zone_rect[z].y;
        for (int j = 0; j < ky; ++j)
          for (int i = 0; i < kx; ++i) {
            const double fu = (i + 0.5) / kx - 0.5, fv = (j + 0.5) / ky - 0.5;
            const double sx = x + fu * ux + fv * vx, sy = y + fu * uy + fv * vy;
            if (inside(sx, sy)) {
              const double px = (sx - pool_off) * pool_inv - ox, py = (sy - pool_off) * pool_inv - oy;
              if (px >= 0 && py >= 0 && px < zp.cols - 1 && py < zp.rows - 1) {
                retinaSplat(zp, px, py, w * sub);
                deposited += w * sub;
              } else {
                lost += w * sub;  // never: the node's plane holds its rays' cells (above)
              }
            } else {
              lost += w * sub;
            }
          }
      }
    }
    // Each node's plane blurred by its elliptical Gaussian (filter2D: the kernel is
    // centro-symmetric, so correlation is convolution), summed, brought back to the canvas.
    cv::Mat total(coarse_size, CV_64F, cv::Scalar(0));
    for (std::size_t z = 0; z < n_zones; ++z) {
      if (zone_plane[z].empty()) continue;
      cv::Mat out;
      cv::filter2D(zone_plane[z], out, CV_64F, ellipticalGaussianKernel(kcov[z]), cv::Point(-1, -1), 0,
                   cv::BORDER_CONSTANT);
      cv::Mat dst = total(zone_rect[z]);
      dst += out;
    }
    if (kpool > 1) {
      const double power = cv::sum(total)[0];
      cv::Mat up;
      cv::resize(total, up, cv::Size(total.cols * kpool, total.rows * kpool), 0, 0, cv::INTER_LINEAR);
      cv::Mat out = up(cv::Rect(0, 0, canvas_size.width, canvas_size.height));  // a view: no copy
      const double now = cv::sum(out)[0];
      if (now > 0) out *= power / now;
      blurred_planes[li] = out;
    } else {
      blurred_planes[li] = total;
    }
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
  std::vector<double> speckle_dof(lasers.size(), 1.0);
  if (o.speckle_patterns > 0 && o.speckle_grain_pupil)
    for (std::size_t li = 0; li < lasers.size(); ++li)
      speckle_dof[li] = speckleDegreesOfFreedom(60.0 / ppx, 60.0 / ppy, lasers[li], scene.eye.pupil_diameter_mm);
  r.speckle_dof = o.speckle_patterns > 0 ? speckle_dof : std::vector<double>();
  // Grain one canvas pixel (each pixel one fully developed pattern per pattern), or set by the
  // pupil and integrated over the pixel (speckle_grain.h): M degrees of freedom each. One
  // field per laser (own seed), drawn concurrently.
  std::vector<cv::Mat> speckle_fields(o.speckle_patterns > 0 ? lasers.size() : 0);
  tbb::parallel_for(std::size_t{0}, speckle_fields.size(), [&](std::size_t li) {
    speckle_fields[li] =
        o.speckle_grain_pupil
            ? integratedSpeckleField(canvas_size, speckle_dof[li] * o.speckle_patterns, o.speckle_seed + 7919 * li)
            : speckleField(canvas_size, o.speckle_patterns, o.speckle_seed + 7919 * li);
  });
  for (std::size_t li = 0; li < blurred_planes.size(); ++li) {
    cv::Mat blurred = std::move(blurred_planes[li]);
    if (o.speckle_patterns > 0) {
      const cv::Mat& s = speckle_fields[li];
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
    cv::Mat any = channels[0] + channels[1] + channels[2];
    double peak = 0;
    cv::minMaxLoc(any, nullptr, &peak);
    lit = any > 1e-3 * peak;  // where the peripheral display lights the retina
    r.speckle_contrast = speckleContrast(speckle_sum, lit);
    // The mean of the lasers' independent fields: variance sum 1/(M_l N) / L^2.
    double var = 0;
    for (double m : speckle_dof) var += 1.0 / (m * o.speckle_patterns);
    r.speckle_expected = std::sqrt(var) / static_cast<double>(lasers.size());
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
