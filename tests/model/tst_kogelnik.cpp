// Kogelnik coupled-wave theory: closed forms, nulls, bounds, symmetry, continuity, 3-D = planar.
#include <QtTest>

#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "model/physics/grating.h"
#include "model/physics/grating_request.h"
#include "model/units.h"

namespace tst_kogelnik {

using namespace fovea;

namespace {

PlanarGrating planar(double n0, double n1, double d_um, double period_nm, double slant_deg, double probe_deg,
                     double lambda_nm, Polarization pol = Polarization::S) {
  PlanarGrating g;
  g.film.n0 = n0;
  g.film.n1 = n1;
  g.film.thickness_um = d_um;
  g.period_nm = period_nm;
  g.slant_deg = slant_deg;
  g.probe_deg = probe_deg;
  g.wavelength_nm = lambda_nm;
  g.polarization = pol;
  return g;
}

// Kogelnik's nu and xi written out independently of the library (Eqs. 23, 24, 42, 54).
struct NuXi {
  double nu, xi;
};
NuXi kogelnikNuXi(const PlanarGrating& g) {
  const double lam = g.wavelength_nm * 1e-3, beta = 2 * kPi * g.film.n0 / lam, k = 2 * kPi / (g.period_nm * 1e-3);
  const double th = g.probe_deg * kDeg, ph = g.slant_deg * kDeg;
  const double cr = std::cos(th), cs = std::cos(th) - k / beta * std::cos(ph);
  const double vt = k * std::cos(ph - th) - k * k * lam / (4 * kPi * g.film.n0);
  return {kPi * g.film.n1 * g.film.thickness_um / (lam * std::sqrt(cr * std::abs(cs))),
          std::abs(vt) * g.film.thickness_um / (2 * std::abs(cs))};
}

// Angle theta that solves f(theta) = 0 by bisection on [a, b] (f changes sign).
template <class F>
double bisect(F f, double a, double b) {
  double fa = f(a);
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (a + b), fm = f(m);
    if ((fm < 0) == (fa < 0)) {
      a = m;
      fa = fm;
    } else {
      b = m;
    }
  }
  return 0.5 * (a + b);
}
}  // namespace

class TestKogelnik : public QObject {
  Q_OBJECT
 private slots:
  void unslantedTransmissionOnBraggNuHalfPiIsTotal() {
    // Unslanted transmission grating (phi = 90 deg): Bragg at sin(theta) = lambda / (2 n0 Lambda).
    const double n0 = 1.5, n1 = 0.01, lambda = 532.0, period = 1000.0;
    const double theta = std::asin(lambda / (2 * n0 * period));
    const double d_um = 0.5 * lambda * 1e-3 * std::cos(theta) / n1;  // nu = pi n1 d / (lambda cos theta) = pi/2
    for (Polarization pol : {Polarization::S}) {
      const PlanarDiffraction r = diffractPlanar(planar(n0, n1, d_um, period, 90.0, theta / kDeg, lambda, pol));
      QVERIFY(!r.grating.reflection());
      QVERIFY(std::abs(r.grating.kogelnik.nu - kPi / 2) < 1e-12);
      QVERIFY(r.grating.kogelnik.xi < 1e-10);
      QVERIFY2(std::abs(r.grating.kogelnik.efficiency - 1.0) < 1e-12,
               qPrintable(QString::number(r.grating.kogelnik.efficiency, 'g', 17)));
      // The diffracted wave leaves mirrored about the fringe planes: at -theta.
      QVERIFY(r.diffracted_deg.has_value());
      QVERIFY(std::abs(*r.diffracted_deg + theta / kDeg) < 1e-9);
    }
    // Thickness sweep on Bragg follows sin^2(nu) (Kogelnik Eq. 44).
    for (double f : {0.1, 0.37, 1.0, 1.5, 2.0, 3.3}) {
      const PlanarDiffraction r = diffractPlanar(planar(n0, n1, f * d_um, period, 90.0, theta / kDeg, lambda));
      const double nu = f * kPi / 2;
      QVERIFY(std::abs(r.grating.kogelnik.efficiency - std::pow(std::sin(nu), 2)) < 1e-12);
    }
  }

  void pPolarisationScalesCouplingByCos2ThetaMinusPhi() {
    // On Bragg the p coupling factor is |cos 2(theta - phi)| (Kogelnik Sec. 4).
    const double n0 = 1.5, n1 = 0.01, lambda = 532.0, period = 400.0;
    const double theta = std::asin(lambda / (2 * n0 * period));
    const double d_um = 20.0;
    const PlanarDiffraction s = diffractPlanar(planar(n0, n1, d_um, period, 90.0, theta / kDeg, lambda));
    const PlanarDiffraction p =
        diffractPlanar(planar(n0, n1, d_um, period, 90.0, theta / kDeg, lambda, Polarization::P));
    const double factor = std::abs(std::cos(2 * (theta - kPi / 2)));
    QVERIFY(std::abs(p.grating.kogelnik.nu - s.grating.kogelnik.nu * factor) < 1e-12);
    QVERIFY(std::abs(p.grating.kogelnik.efficiency - std::pow(std::sin(s.grating.kogelnik.nu * factor), 2)) < 1e-12);
    const PlanarDiffraction u =
        diffractPlanar(planar(n0, n1, d_um, period, 90.0, theta / kDeg, lambda, Polarization::Unpolarized));
    QVERIFY(std::abs(u.grating.kogelnik.efficiency -
                     0.5 * (s.grating.kogelnik.efficiency + p.grating.kogelnik.efficiency)) < 1e-15);
  }

  void reflectionOnBraggIsTanhSquared() {
    const double n0 = 1.52, n1 = 0.02, lambda = 532.0;
    // Unslanted (phi = 0), normal incidence: Lambda = lambda / (2 n0).
    for (double d : {1.0, 5.0, 16.0, 40.0, 400.0}) {
      const PlanarDiffraction r = diffractPlanar(planar(n0, n1, d, lambda / (2 * n0), 0.0, 0.0, lambda));
      const double nu = kPi * n1 * d / (lambda * 1e-3);
      QVERIFY(r.grating.reflection());
      QVERIFY(std::abs(r.grating.kogelnik.nu - nu) < 1e-9 * nu);
      QVERIFY(std::abs(r.grating.kogelnik.efficiency - std::pow(std::tanh(nu), 2)) < 1e-12);
      QVERIFY(std::abs(std::abs(*r.diffracted_deg) - 180.0) < 1e-9);
    }
    // Slanted reflection grating on Bragg: cos(theta - phi) = K / (2 beta), nu = kappa d / sqrt(c_R |c_S|).
    const double phi = 10.0 * kDeg, k_over_beta = 1.9;
    const double period = lambda / (n0 * k_over_beta);
    const double theta = phi + std::acos(k_over_beta / 2);
    const double cr = std::cos(theta), cs = std::cos(theta) - k_over_beta * std::cos(phi);
    QVERIFY(cs < 0);
    for (double d : {3.0, 16.0, 60.0}) {
      const PlanarDiffraction r = diffractPlanar(planar(n0, n1, d, period, phi / kDeg, theta / kDeg, lambda));
      const double nu = kPi * n1 * d / (lambda * 1e-3 * std::sqrt(cr * -cs));
      QVERIFY(r.grating.kogelnik.xi < 1e-9);
      QVERIFY(std::abs(r.grating.kogelnik.efficiency - std::pow(std::tanh(nu), 2)) < 1e-11);
    }
  }

  void firstNullsOffBragg() {
    // Transmission: eta = sin^2(sqrt(nu^2 + xi^2)) / (1 + xi^2/nu^2) vanishes first where
    // sqrt(nu^2 + xi^2) = pi. Find that probe angle from Kogelnik's formulas written out here.
    const double n0 = 1.5, n1 = 0.01, lambda = 532.0, period = 1000.0;
    const double tb = std::asin(lambda / (2 * n0 * period)) / kDeg;
    const double d_um = 0.5 * lambda * 1e-3 * std::cos(tb * kDeg) / n1;  // nu = pi/2 on Bragg
    auto g = [&](double th) { return planar(n0, n1, d_um, period, 90.0, th, lambda); };
    const auto root = [&](double th) {
      const NuXi p = kogelnikNuXi(g(th));
      return std::hypot(p.nu, p.xi) - kPi;
    };
    for (double dir : {+1.0, -1.0}) {
      const double th0 = bisect(root, tb, tb + dir * 5.0);
      const double eta = diffractPlanar(g(th0)).grating.kogelnik.efficiency;
      QVERIFY2(eta < 1e-12, qPrintable(QString("null at %1 deg: eta %2").arg(th0).arg(eta)));
      // and it is a true first null: half-way to Bragg the efficiency is large.
      QVERIFY(diffractPlanar(g(0.5 * (th0 + tb))).grating.kogelnik.efficiency > 0.3);
      const NuXi p = kogelnikNuXi(g(th0));
      QVERIFY(std::abs(p.xi - kPi * std::sqrt(3.0) / 2) < 2e-2);  // nu stays ~pi/2 near Bragg
    }
    // Reflection: eta = 0 where sqrt(xi^2 - nu^2) = pi (the sinh turned sin), Kogelnik Eq. 56.
    const double lam_r = 532.0, d_r = 16.0, n1_r = 0.02;
    auto gr = [&](double lam_nm) { return planar(n0, n1_r, d_r, lam_r / (2 * n0), 0.0, 0.0, lam_nm); };
    const auto root_r = [&](double lam_nm) {
      const NuXi p = kogelnikNuXi(gr(lam_nm));
      return p.xi * p.xi - p.nu * p.nu - kPi * kPi;
    };
    const double lam0 = bisect(root_r, lam_r + 0.1, lam_r + 40.0);
    QVERIFY(root_r(lam_r + 0.1) < 0);
    QVERIFY(diffractPlanar(gr(lam0)).grating.kogelnik.efficiency < 1e-12);
    QVERIFY(diffractPlanar(gr(0.5 * (lam0 + lam_r))).grating.kogelnik.efficiency > 0.1);
  }

  void reportedNuXiMatchKogelnik() {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 2000; ++i) {
      const PlanarGrating g = planar(1.3 + 0.5 * u(rng), 0.05 * u(rng), 100 * u(rng), 100 + 2900 * u(rng),
                                     -180 + 360 * u(rng), -89 + 178 * u(rng), 400 + 400 * u(rng));
      const NuXi ref = kogelnikNuXi(g);
      const PlanarDiffraction r = diffractPlanar(g);
      if (!std::isfinite(ref.nu) || r.grating.kogelnik.nu == 0.0) continue;
      QVERIFY(std::abs(r.grating.kogelnik.nu - ref.nu) <= 1e-9 * (1 + ref.nu));
      QVERIFY(std::abs(r.grating.kogelnik.xi - ref.xi) <= 1e-9 * (1 + ref.xi));
    }
  }

  void efficiencyBoundedAndEnergyConserved() {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 20000; ++i) {
      PlanarGrating g = planar(1.3 + 0.5 * u(rng), 0.1 * u(rng), 200 * u(rng), 80 + 3000 * u(rng), -180 + 360 * u(rng),
                               -89.9 + 179.8 * u(rng), 400 + 400 * u(rng), static_cast<Polarization>(i % 3));
      const PlanarDiffraction r = diffractPlanar(g);
      const double eta = r.grating.kogelnik.efficiency;
      QVERIFY2(eta >= 0.0 && eta <= 1.0, qPrintable(QString::number(eta)));
      QVERIFY(std::abs(eta + r.grating.kogelnik.zero_order - 1.0) < 1e-9);  // lossless
      g.film.alpha_per_um = 0.05 * u(rng);
      const PlanarDiffraction a = diffractPlanar(g);
      const double ea = a.grating.kogelnik.efficiency, za = a.grating.kogelnik.zero_order;
      QVERIFY2(std::isfinite(ea) && std::isfinite(za), "finite with absorption");
      QVERIFY2(ea >= 0.0 && ea + za <= 1.0 + 1e-9, qPrintable(QString("%1 + %2").arg(ea).arg(za)));
    }
  }

  void absorbingPathEqualsLosslessAtZeroAbsorption() {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 5000; ++i) {
      const double cr = 0.05 + 0.95 * u(rng);
      const double cs = (u(rng) < 0.5 ? -1 : 1) * (0.02 + 1.5 * u(rng));
      const double vt = (u(rng) - 0.5) * 0.5, kappa = 0.2 * u(rng), d = 60 * u(rng);
      const kogelnik::Result a = kogelnik::absorbing(cr, cs, vt, kappa, 0.0, d);
      const kogelnik::Result l = kogelnik::lossless(cr, cs, vt, kappa, d);
      QVERIFY2(std::abs(a.efficiency - l.efficiency) < 1e-10,
               qPrintable(QString("%1 vs %2 (cs %3)").arg(a.efficiency).arg(l.efficiency).arg(cs)));
      QVERIFY(std::abs(a.zero_order - l.zero_order) < 1e-10);
    }
  }

  void absorptionClosedFormAndMonotone() {
    // Unslanted transmission on Bragg in an absorbing film: eta = sin^2(nu) exp(-2 alpha d / cos theta)
    // (Kogelnik Eq. 45, alpha the amplitude constant).
    const double n0 = 1.5, n1 = 0.01, lambda = 532.0, period = 1000.0;
    const double theta = std::asin(lambda / (2 * n0 * period));
    PlanarGrating g = planar(n0, n1, 20.0, period, 90.0, theta / kDeg, lambda);
    const double nu = kPi * n1 * 20.0 / (lambda * 1e-3 * std::cos(theta));
    double previous = 2.0;
    for (double alpha : {0.0, 0.001, 0.005, 0.01, 0.03, 0.1}) {
      g.film.alpha_per_um = alpha;
      const double eta = diffractPlanar(g).grating.kogelnik.efficiency;
      QVERIFY(std::abs(eta - std::pow(std::sin(nu), 2) * std::exp(-2 * alpha * 20.0 / std::cos(theta))) < 1e-12);
      QVERIFY(eta < previous);
      previous = eta;
    }
    // Reflection on Bragg: efficiency falls monotonically with absorption, below tanh^2(nu).
    PlanarGrating r = planar(n0, 0.02, 16.0, lambda / (2 * n0), 0.0, 0.0, lambda);
    previous = 2.0;
    for (double alpha : {0.0, 0.001, 0.005, 0.01, 0.03, 0.1, 1.0}) {
      r.film.alpha_per_um = alpha;
      const auto k = diffractPlanar(r).grating.kogelnik;
      QVERIFY(k.efficiency < previous);
      QVERIFY(k.efficiency + k.zero_order <= 1.0 + 1e-12);
      previous = k.efficiency;
    }
  }

  void reflectionBranchChangeIsContinuous() {
    // c_R = 1, c_S = -1: nu = kappa d, xi = |vartheta| d / 2. Sweep xi through nu.
    const double d = 10.0, kappa = 0.12;  // nu = 1.2
    const double nu = kappa * d;
    const double at = nu * nu / (1 + nu * nu);  // limit at nu = xi: 1 / (1 + 1/nu^2)
    for (double rel : {-1e-3, -1e-6, -1e-9, 0.0, 1e-9, 1e-6, 1e-3}) {
      const double xi = nu * (1 + rel);
      const double vt = 2 * xi / d;
      const double eta = kogelnik::lossless(1.0, -1.0, vt, kappa, d).efficiency;
      QVERIFY2(std::abs(eta - at) < 3 * std::abs(rel) + 1e-14,
               qPrintable(QString("rel %1: %2 vs %3").arg(rel).arg(eta).arg(at)));
      QVERIFY(std::abs(kogelnik::absorbing(1.0, -1.0, vt, kappa, 0.0, d).efficiency - eta) < 1e-12);
    }
    // Kogelnik's two branches on either side, written out.
    const double xi_lo = 0.8 * nu, xi_hi = 1.25 * nu;
    const double s_lo = std::sinh(std::sqrt(nu * nu - xi_lo * xi_lo));
    const double s_hi = std::sin(std::sqrt(xi_hi * xi_hi - nu * nu));
    QVERIFY(std::abs(kogelnik::lossless(1, -1, 2 * xi_lo / d, kappa, d).efficiency -
                     1 / (1 + (1 - xi_lo * xi_lo / (nu * nu)) / (s_lo * s_lo))) < 1e-13);
    QVERIFY(std::abs(kogelnik::lossless(1, -1, 2 * xi_hi / d, kappa, d).efficiency -
                     1 / (1 + (xi_hi * xi_hi / (nu * nu) - 1) / (s_hi * s_hi))) < 1e-13);  // sinh^2 = -sin^2
  }

  void limitsStayFinite() {
    // nu -> 0: eta ~ nu^2 (transmission on Bragg), exactly 0 at nu = 0.
    const double n0 = 1.5, lambda = 532.0, period = 1000.0;
    const double theta = std::asin(lambda / (2 * n0 * period)) / kDeg;
    for (double n1 : {1e-6, 1e-9, 1e-12}) {
      const auto k = diffractPlanar(planar(n0, n1, 10.0, period, 90.0, theta, lambda)).grating.kogelnik;
      QVERIFY(std::abs(k.efficiency / (k.nu * k.nu) - 1.0) < 1e-6);
    }
    QCOMPARE(diffractPlanar(planar(n0, 0.0, 10.0, period, 90.0, theta, lambda)).grating.kogelnik.efficiency, 0.0);
    QCOMPARE(diffractPlanar(planar(n0, 0.01, 0.0, period, 90.0, theta, lambda)).grating.kogelnik.efficiency, 0.0);
    // Very thick reflection grating on Bragg: -> 1 without overflow; off Bragg stays bounded.
    const auto thick = diffractPlanar(planar(n0, 0.02, 1e5, lambda / (2 * n0), 0.0, 0.0, lambda)).grating.kogelnik;
    QCOMPARE(thick.efficiency, 1.0);
    // 20 deg off: xi ~ 9 nu, so eta <= nu^2 / (xi^2 - nu^2) ~ 0.013.
    const auto thick_off = diffractPlanar(planar(n0, 0.02, 1e5, lambda / (2 * n0), 0.0, 20.0, lambda)).grating.kogelnik;
    QVERIFY(thick_off.xi > 5 * thick_off.nu);
    QVERIFY(std::isfinite(thick_off.efficiency) && thick_off.efficiency >= 0 &&
            thick_off.efficiency <=
                thick_off.nu * thick_off.nu / (thick_off.xi * thick_off.xi - thick_off.nu * thick_off.nu));
    PlanarGrating abs_thick = planar(n0, 0.02, 1e5, lambda / (2 * n0), 0.0, 0.0, lambda);
    abs_thick.film.alpha_per_um = 0.01;
    const auto ka = diffractPlanar(abs_thick).grating.kogelnik;
    QVERIFY(std::isfinite(ka.efficiency) && std::isfinite(ka.zero_order) && ka.efficiency < 1.0);
    // Grazing probe (theta -> 90 deg): finite.
    const auto graze = diffractPlanar(planar(n0, 0.02, 16.0, 300.0, 30.0, 89.999, lambda)).grating.kogelnik;
    QVERIFY(std::isfinite(graze.efficiency) && graze.efficiency >= 0 && graze.efficiency <= 1);
  }

  void mirrorSymmetry() {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 500; ++i) {
      const double n0 = 1.4 + 0.3 * u(rng), n1 = 0.03 * u(rng), d = 50 * u(rng), lam = 400 + 300 * u(rng);
      const double th = -80 + 160 * u(rng), period = 150 + 1500 * u(rng);
      const auto pol = static_cast<Polarization>(i % 3);
      // Unslanted reflection grating (K along z) is symmetric under x -> -x: theta and -theta agree.
      const auto a = diffractPlanar(planar(n0, n1, d, period, 0.0, th, lam, pol));
      const auto b = diffractPlanar(planar(n0, n1, d, period, 0.0, -th, lam, pol));
      QVERIFY(std::abs(a.grating.kogelnik.efficiency - b.grating.kogelnik.efficiency) < 1e-14);
      QCOMPARE(a.diffracted_deg.has_value(), b.diffracted_deg.has_value());
      if (a.diffracted_deg && std::abs(std::abs(*a.diffracted_deg) - 180.0) > 1e-9)
        QVERIFY(std::abs(*a.diffracted_deg + *b.diffracted_deg) < 1e-9);
      // Unslanted transmission grating: the mirror image of (theta, K at +90) is (-theta, K at -90).
      const auto c = diffractPlanar(planar(n0, n1, d, period, 90.0, th, lam, pol));
      const auto e = diffractPlanar(planar(n0, n1, d, period, -90.0, -th, lam, pol));
      QVERIFY(std::abs(c.grating.kogelnik.efficiency - e.grating.kogelnik.efficiency) < 1e-14);
      if (c.diffracted_deg) QVERIFY(std::abs(*c.diffracted_deg + *e.diffracted_deg) < 1e-9);
    }
  }

  void threeDimensionalEqualsPlanar() {
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 3000; ++i) {
      PlanarGrating g = planar(1.3 + 0.5 * u(rng), 0.05 * u(rng), 80 * u(rng), 100 + 2000 * u(rng), -180 + 360 * u(rng),
                               -89 + 178 * u(rng), 400 + 400 * u(rng), static_cast<Polarization>(i % 3));
      if (i % 2) g.film.alpha_per_um = 0.02 * u(rng);
      const auto p = diffractPlanar(g);
      const double lam = g.wavelength_nm * 1e-3, beta = 2 * kPi * g.film.n0 / lam;
      const double k = 2 * kPi / (g.period_nm * 1e-3);
      const Eigen::Vector3d rho(beta * std::sin(g.probe_deg * kDeg), 0, beta * std::cos(g.probe_deg * kDeg));
      const Eigen::Vector3d kv(k * std::sin(g.slant_deg * kDeg), 0, k * std::cos(g.slant_deg * kDeg));
      // In plane, and the same configuration rotated about the film normal by a random angle.
      const Eigen::Matrix3d rz = Eigen::AngleAxisd(2 * kPi * u(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
      for (const Eigen::Matrix3d& rot : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), rz}) {
        const auto t = diffract3d(rot * rho, rot * kv, g.film, lam, g.polarization);
        QVERIFY(std::abs(t.kogelnik.efficiency - p.grating.kogelnik.efficiency) < 1e-10);
        QVERIFY(std::abs(t.kogelnik.nu - p.grating.kogelnik.nu) < 1e-9 * (1 + p.grating.kogelnik.nu));
        QVERIFY(std::abs(t.kogelnik.xi - p.grating.kogelnik.xi) < 1e-9 * (1 + p.grating.kogelnik.xi));
        QCOMPARE(t.reflection(), p.grating.reflection());
        QCOMPARE(t.evanescent, p.grating.evanescent);
        if (!t.evanescent) QVERIFY((t.diffracted - rot * p.grating.diffracted).norm() < 1e-9 * beta);
      }
      // A probe travelling towards -z sees the z-mirrored film: same efficiency.
      const Eigen::Vector3d mz(1, 1, -1);
      const auto m = diffract3d(rho.cwiseProduct(mz), kv.cwiseProduct(mz), g.film, lam, g.polarization);
      QVERIFY(std::abs(m.kogelnik.efficiency - p.grating.kogelnik.efficiency) < 1e-10);
      if (!m.evanescent) QVERIFY((m.diffracted - p.grating.diffracted.cwiseProduct(mz)).norm() < 1e-9 * beta);
    }
  }

  void requestValidationNamesTheArgument() {
    GratingRequest r;
    r.grating = planar(1.5, 0.02, 16, 177, 0, 0, 532);
    QVERIFY(!validateGratingRequest(r, true));
    auto bad = r;
    bad.grating.film.thickness_um = -1;
    QCOMPARE(validateGratingRequest(bad, true)->key, std::string("thickness_um"));
    QVERIFY(validateGratingRequest(bad, true)->message.find("--thickness-um") == 0);
    bad = r;
    bad.grating.film.n1 = 1.5;
    QCOMPARE(validateGratingRequest(bad, false)->key, std::string("n1"));
    bad = r;
    bad.grating.period_nm = std::nan("");
    QCOMPARE(validateGratingRequest(bad, false)->key, std::string("period_nm"));
    auto parsed = gratingRequestFromJson(nlohmann::json::parse(
        R"({"n0":1.5,"n1":0.02,"thickness_um":16,"period_nm":177,"slant_deg":0,"probe_deg":0,"wavelength_nm":532,"polarization":"x"})"));
    QCOMPARE(std::get<GratingArgError>(parsed).key, std::string("polarization"));
    parsed = gratingRequestFromJson(nlohmann::json::parse(R"({"n0":1.5})"));
    QCOMPARE(std::get<GratingArgError>(parsed).key, std::string("n1"));
  }
};

QTEST_GUILESS_MAIN(TestKogelnik)

}  // namespace tst_kogelnik
#include "tst_kogelnik.moc"
