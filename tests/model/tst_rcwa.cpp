// RCWA against closed forms: Fresnel and Airy (zero modulation), Beer–Lambert, energy
// conservation, reciprocity, the doubling assembly against explicit slices, convergence.
#include <QtTest>

#include <cmath>
#include <complex>
#include <random>

#include "model/rigorous/rcwa.h"
#include "model/units.h"
#include "tests/model/rcwa_cases.h"

namespace tst_rcwa {

using namespace fovea::rigorous;
using fovea::degToRad;
using fovea::kPi;
using fovea::testing::strongSlanted;
using cd = std::complex<double>;

namespace {

// Generic two-interface (Airy) film for the amplitude u (E_y for TE, Z0 H_y for TM):
// continuity of u and of its partner v = ±Y u gives r_ij = (Y_i − Y_j)/(Y_i + Y_j),
// t_ij = 2 Y_i/(Y_i + Y_j), with Y = k_z (TE) or k_z/ε (TM); the film adds e^{iβ},
// β = k0 k_z d. Power: R = |r|², T = |t|² Re Y_s / Y_c.
struct Airy {
  double R, T;
};
Airy airy(double nc, cd nf, double ns, double kx, double d_um, double lambda_nm, bool te) {
  auto kz = [&](cd n) {
    cd g = std::sqrt(n * n - kx * kx);
    if (g.imag() < 0) g = -g;
    return g;
  };
  auto Y = [&](cd n) { return te ? kz(n) : kz(n) / (n * n); };
  const cd yc = Y(nc), yf = Y(nf), ys = Y(ns);
  const cd r01 = (yc - yf) / (yc + yf), r12 = (yf - ys) / (yf + ys);
  const cd t01 = 2.0 * yc / (yc + yf), t12 = 2.0 * yf / (yf + ys);
  const cd beta = 2.0 * kPi / (lambda_nm * 1e-3) * kz(nf) * d_um;
  const cd e1 = std::exp(cd(0, 1) * beta), e2 = e1 * e1;
  const cd r = (r01 + r12 * e2) / (1.0 + r01 * r12 * e2);
  const cd t = t01 * t12 * e1 / (1.0 + r01 * r12 * e2);
  return {std::norm(r), std::norm(t) * ys.real() / yc.real()};
}

}  // namespace

class TestRcwa : public QObject {
  Q_OBJECT
 private slots:
  void fresnelSingleInterface_data() {
    QTest::addColumn<bool>("te");
    QTest::newRow("TE") << true;
    QTest::newRow("TM") << false;
  }
  // n1 = 0 and film index = substrate index: one interface, textbook Fresnel in angles.
  void fresnelSingleInterface() {
    QFETCH(bool, te);
    for (double deg : {0.0, 30.0, 56.3, 80.0}) {
      RcwaProblem p;
      p.n0 = 1.5;
      p.n1 = 0.0;
      p.n_cover = 1.0;
      p.n_substrate = 1.5;
      p.thickness_um = 2.0;
      p.slant_deg = 40.0;
      p.period_nm = 700.0;
      p.polarization = te ? RcwaPolarization::TE : RcwaPolarization::TM;
      p.setCoverAngleDeg(deg);
      const RcwaResult r = solveRcwa(p, {3, 4, false});
      const double ti = degToRad(deg), tt = std::asin(std::sin(ti) / 1.5);
      const double rs = (std::cos(ti) - 1.5 * std::cos(tt)) / (std::cos(ti) + 1.5 * std::cos(tt));
      const double rp = (1.5 * std::cos(ti) - std::cos(tt)) / (1.5 * std::cos(ti) + std::cos(tt));
      const double R = te ? rs * rs : rp * rp;
      QVERIFY2(std::abs(r.efficiency(0, true) - R) < 1e-12, qPrintable(QString::number(deg)));
      QVERIFY(std::abs(r.efficiency(0, false) - (1.0 - R)) < 1e-12);
      QVERIFY(std::abs(r.efficiency(1, false)) < 1e-20);  // no modulation: no diffraction
      // The refracted wave leaves at Snell's angle.
      QVERIFY(std::abs(r.find(0, false)->angle_deg - tt * 180.0 / kPi) < 1e-9);
      QVERIFY(std::abs(r.find(0, true)->angle_deg - (180.0 - deg)) < 1e-9 || deg == 0.0);
    }
    // Brewster: R_p = 0 at atan(1.5).
    RcwaProblem b;
    b.n0 = 1.5;
    b.n_cover = 1.0;
    b.n_substrate = 1.5;
    b.polarization = te ? RcwaPolarization::TE : RcwaPolarization::TM;
    b.setCoverAngleDeg(std::atan(1.5) * 180.0 / kPi);
    const double rb = solveRcwa(b, {1, 1, false}).efficiency(0, true);
    if (te)
      QVERIFY(rb > 0.1);
    else
      QVERIFY(rb < 1e-20);
  }

  void airyThinFilm_data() {
    QTest::addColumn<bool>("te");
    QTest::addColumn<double>("kappa");
    QTest::newRow("TE lossless") << true << 0.0;
    QTest::newRow("TM lossless") << false << 0.0;
    QTest::newRow("TE absorbing") << true << 0.05;
    QTest::newRow("TM absorbing") << false << 0.05;
  }
  // n_c ≠ n0 ≠ n_s, no modulation: the Airy sum of a single film.
  void airyThinFilm() {
    QFETCH(bool, te);
    QFETCH(double, kappa);
    for (double d : {0.05, 0.3, 1.7}) {
      for (double deg : {0.0, 40.0, 75.0}) {
        RcwaProblem p;
        p.n0 = cd(2.0, kappa);
        p.n1 = 0.0;
        p.n_cover = 1.0;
        p.n_substrate = 1.5;
        p.thickness_um = d;
        p.wavelength_nm = 633.0;
        p.period_nm = 350.0;
        p.slant_deg = 70.0;
        p.polarization = te ? RcwaPolarization::TE : RcwaPolarization::TM;
        p.setCoverAngleDeg(deg);
        const RcwaResult r = solveRcwa(p, {2, 8, false});
        const Airy a = airy(1.0, p.n0, 1.5, p.kx_over_k0, d, 633.0, te);
        QVERIFY2(std::abs(r.efficiency(0, true) - a.R) < 1e-11,
                 qPrintable(QString("R %1 vs %2").arg(r.efficiency(0, true)).arg(a.R)));
        QVERIFY2(std::abs(r.efficiency(0, false) - a.T) < 1e-11,
                 qPrintable(QString("T %1 vs %2").arg(r.efficiency(0, false)).arg(a.T)));
        if (kappa == 0.0)
          QVERIFY(std::abs(r.total_efficiency - 1.0) < 1e-12);
        else
          QVERIFY(r.total_efficiency < 1.0 - 1e-3);
      }
    }
  }

  // An index-matched absorbing film: Beer–Lambert, T = exp(−2 k0 Im(k_z) d), up to the tiny
  // reflection from the κ step (|r|² ~ (κ/2n)²).
  void beerLambert() {
    RcwaProblem p;
    p.n0 = cd(1.5, 1e-4);
    p.n_cover = p.n_substrate = 1.5;
    p.thickness_um = 500.0;
    p.setFilmAngleDeg(30.0);
    const RcwaResult r = solveRcwa(p, {0, 1, false});
    const cd kz = std::sqrt(p.n0 * p.n0 - p.kx_over_k0 * p.kx_over_k0);
    const double expected = std::exp(-2.0 * (2.0 * kPi / 0.532) * kz.imag() * 500.0);
    QVERIFY(expected > 0.1 && expected < 0.5);
    QVERIFY2(std::abs(r.efficiency(0, false) - expected) < 1e-6,
             qPrintable(QString("%1 vs %2").arg(r.efficiency(0, false)).arg(expected)));
  }

  void energyConservation_data() {
    QTest::addColumn<bool>("te");
    QTest::newRow("TE") << true;
    QTest::newRow("TM") << false;
  }
  // Strong slanted grating with several propagating orders on both sides.
  void energyConservation() {
    QFETCH(bool, te);
    RcwaProblem p = strongSlanted(te ? RcwaPolarization::TE : RcwaPolarization::TM);
    const RcwaResult r = solveRcwa(p, {12, 32, false});
    int propagating = 0;
    double diffracted = 0.0;
    for (const RcwaOrder& o : r.orders) {
      QVERIFY(o.efficiency >= 0.0);
      ++propagating;
      if (o.order != 0) diffracted += o.efficiency;
    }
    QVERIFY(propagating >= 4);
    QVERIFY(diffracted > 0.05);  // the grating does diffract
    QVERIFY2(std::abs(r.total_efficiency - 1.0) < 1e-10, qPrintable(QString::number(r.total_efficiency - 1.0, 'g', 3)));
    // Absorbing: strictly less, and the loss grows with the extinction coefficient.
    p.n0 = cd(1.5, 1e-3);
    const double t1 = solveRcwa(p, {12, 32, false}).total_efficiency;
    p.n0 = cd(1.5, 3e-3);
    const double t3 = solveRcwa(p, {12, 32, false}).total_efficiency;
    QVERIFY(t1 < 1.0 - 1e-3 && t3 < t1 && t3 > 0.5);
  }

  // Thick films: the S-matrix must not blow up (a T-matrix would overflow exp(|γ| k0 d)).
  void thickFilmStable() {
    RcwaProblem p = strongSlanted(RcwaPolarization::TM);
    p.thickness_um = 1000.0;
    p.n1 = 0.01;
    const RcwaResult r = solveRcwa(p, {8, 1 << 14, false});
    QVERIFY(std::isfinite(r.total_efficiency));
    QVERIFY(std::abs(r.total_efficiency - 1.0) < 1e-8);
    for (const RcwaOrder& o : r.orders) QVERIFY(std::isfinite(o.efficiency) && o.efficiency >= 0.0);
  }

  void reciprocity_data() {
    QTest::addColumn<bool>("te");
    QTest::newRow("TE") << true;
    QTest::newRow("TM") << false;
  }
  // Lorentz reciprocity, absorbing film, different cover and substrate:
  //  reflection:   R_m(k_x0) = R_m(−k_x,m)           (same grating, same side)
  //  transmission: T_m(k_x0) = T'_m(−k_x,m) for the structure seen from the substrate
  //                (z → d − z: cover ↔ substrate, slant φ → 180° − φ; the fringe phase offset
  //                this leaves is a lateral shift and does not change efficiencies).
  void reciprocity() {
    QFETCH(bool, te);
    RcwaProblem p = strongSlanted(te ? RcwaPolarization::TE : RcwaPolarization::TM);
    p.n0 = cd(1.5, 2e-3);
    const RcwaOptions opt{7, 24, false};
    const RcwaResult fwd = solveRcwa(p, opt);
    const double kx_grating = p.wavelength_nm / p.period_nm * std::sin(degToRad(p.slant_deg));
    int checked = 0;
    for (const RcwaOrder& o : fwd.orders) {
      const double kxm = p.kx_over_k0 - o.order * kx_grating;
      RcwaProblem q = p;
      if (o.reflected) {
        q.kx_over_k0 = -kxm;
      } else {
        std::swap(q.n_cover, q.n_substrate);
        q.slant_deg = 180.0 - p.slant_deg;
        q.kx_over_k0 = -kxm;
        if (std::abs(q.kx_over_k0) >= q.n_cover) continue;
      }
      const RcwaResult back = solveRcwa(q, opt);
      const double eb = back.efficiency(o.order, o.reflected);
      QVERIFY2(std::abs(eb - o.efficiency) < 1e-9 * std::max(1.0, o.efficiency),
               qPrintable(QString("order %1 %2: %3 vs %4").arg(o.order).arg(o.reflected).arg(o.efficiency).arg(eb)));
      ++checked;
    }
    QVERIFY(checked >= 4);
  }

  // The 1-D stack (unslanted reflection grating, scalar path): transmission is the same from
  // either side (reciprocity), for an absorbing film between different media, s and p.
  void reciprocityOneDimensionalStack() {
    for (RcwaPolarization pol : {RcwaPolarization::TE, RcwaPolarization::TM}) {
      RcwaProblem p;
      p.n0 = cd(1.5, 3e-3);
      p.n1 = 0.04;
      p.thickness_um = 21 * 0.19;  // whole fringes: z → d − z maps the profile onto itself with φ → 180°
      p.period_nm = 190.0;
      p.wavelength_nm = 555.0;  // Bragg: λ = 2 n0 Λ cos θ_film
      p.slant_deg = 0.0;
      p.n_cover = 1.0;
      p.n_substrate = 1.7;
      p.polarization = pol;
      p.setCoverAngleDeg(20.0);
      const RcwaResult a = solveRcwa(p, {0, 672, false});
      QVERIFY(a.laterally_uniform && a.orders.size() == 2);
      QVERIFY(a.efficiency(0, true) > 0.2);  // a real Bragg mirror near its band
      RcwaProblem q = p;
      std::swap(q.n_cover, q.n_substrate);
      q.slant_deg = 180.0;  // z → d − z
      const RcwaResult b = solveRcwa(q, {0, 672, false});
      QVERIFY2(std::abs(a.efficiency(0, false) - b.efficiency(0, false)) < 1e-12,
               qPrintable(QString("%1 %2 %3 %4")
                              .arg(a.efficiency(0, false), 0, 'g', 15)
                              .arg(b.efficiency(0, false), 0, 'g', 15)
                              .arg(a.efficiency(0, true))
                              .arg(b.efficiency(0, true))));
      QVERIFY(std::abs(a.efficiency(0, true) - b.efficiency(0, true)) > 1e-4);  // R differs (absorption)
    }
  }

  // The O(log M) doubling assembly equals building every slice from scratch.
  void doublingEqualsExplicitSlices() {
    for (RcwaPolarization pol : {RcwaPolarization::TE, RcwaPolarization::TM}) {
      RcwaProblem p = strongSlanted(pol);
      p.n0 = cd(1.5, 1e-3);
      for (int m : {1, 5, 13}) {
        const RcwaResult a = solveRcwa(p, {6, m, false});
        const RcwaResult b = solveRcwa(p, {6, m, true});
        QCOMPARE(a.orders.size(), b.orders.size());
        for (std::size_t i = 0; i < a.orders.size(); ++i)
          QVERIFY(std::abs(a.orders[i].efficiency - b.orders[i].efficiency) < 1e-11);
      }
    }
  }

  // Staircase error of midpoint slicing falls as M^{-2}; truncation error falls fast with N.
  void convergence() {
    RcwaProblem p = strongSlanted(RcwaPolarization::TE);
    auto eta = [&](int n, int m) { return solveRcwa(p, {n, m, false}).efficiency(1, false); };
    const double ref = eta(12, 1 << 14);
    // (Asymptotic from ~16 slices per fringe period along z; Λ_z = Λ/|cos φ| = 840 nm here.)
    const double e64 = std::abs(eta(12, 64) - ref), e128 = std::abs(eta(12, 128) - ref),
                 e256 = std::abs(eta(12, 256) - ref);
    QVERIFY2(e64 / e128 > 3.5 && e64 / e128 < 4.5, qPrintable(QString("%1 %2").arg(e64).arg(e128)));
    QVERIFY(e128 / e256 > 3.5 && e128 / e256 < 4.5);
    const double refN = eta(20, 1 << 10);
    // Truncation: the harmonics couple neighbours through ε_±1 ∝ n0 n1 and ε_±2 ∝ n1², so each
    // extra order gains a factor ~ n1/n0: geometric convergence.
    const double n1 = std::abs(eta(1, 1 << 10) - refN), n2 = std::abs(eta(2, 1 << 10) - refN),
                 n4 = std::abs(eta(4, 1 << 10) - refN);
    QVERIFY2(n1 > 1e-5 && n2 < 0.01 * n1 && n4 < 1e-10, qPrintable(QString("%1 %2 %3").arg(n1).arg(n2).arg(n4)));

    // The automatic choice reaches the requested accuracy.
    RcwaConvergence c;
    c.tolerance = 1e-5;
    c.target_order = 1;
    c.target_reflected = false;
    const RcwaConvergedResult conv = solveRcwaConverged(p, c);
    QVERIFY(conv.converged);
    const double fine = solveRcwa(p, {conv.orders + 8, conv.slices * 8, false}).efficiency(1, false);
    QVERIFY2(std::abs(conv.result.efficiency(1, false) - fine) < 5e-5,
             qPrintable(QString("N %1 M %2: %3 vs %4")
                            .arg(conv.orders)
                            .arg(conv.slices)
                            .arg(conv.result.efficiency(1, false))
                            .arg(fine)));
  }

  // Random lossless gratings (fixed seed), including grazing incidence, thick films, strong
  // modulation and near-zero slants: finite, non-negative, energy conserved; absorbing: < 1.
  void randomGratingsConserveEnergy() {
    std::mt19937_64 rng(20261123);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < 60; ++i) {
      RcwaProblem p;
      p.n0 = 1.3 + 0.4 * u(rng);
      p.n1 = 0.1 * u(rng);
      p.thickness_um = std::pow(10.0, -1.0 + 3.0 * u(rng));  // 0.1 µm … 100 µm
      p.period_nm = 150.0 + 2000.0 * u(rng);
      p.slant_deg = i % 10 == 0 ? 1e-7 : 180.0 * u(rng);
      p.wavelength_nm = 400.0 + 300.0 * u(rng);
      p.n_cover = 1.0 + 0.7 * u(rng);
      p.n_substrate = 1.0 + 0.7 * u(rng);
      p.polarization = i % 2 ? RcwaPolarization::TE : RcwaPolarization::TM;
      p.setCoverAngleDeg(i % 7 == 0 ? 89.9 : -85.0 + 170.0 * u(rng));
      const RcwaResult r = solveRcwa(p, {3, 32, false});
      for (const RcwaOrder& o : r.orders) QVERIFY(std::isfinite(o.efficiency) && o.efficiency >= 0.0);
      QVERIFY2(std::abs(r.total_efficiency - 1.0) < 1e-8,
               qPrintable(QString("case %1: %2").arg(i).arg(r.total_efficiency - 1.0)));
      p.n0 = cd(p.n0.real(), 1e-3);
      const double lossy = solveRcwa(p, {3, 32, false}).total_efficiency;
      QVERIFY(std::isfinite(lossy) && lossy < 1.0 && lossy >= 0.0);
    }
  }

  void badInput() {
    RcwaProblem p;
    p.thickness_um = -1.0;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, solveRcwa(p));
    p = RcwaProblem{};
    p.period_nm = std::nan("");
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, solveRcwa(p));
    p = RcwaProblem{};
    p.kx_over_k0 = 1.6;  // beyond the cover index
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, solveRcwa(p));
    p = RcwaProblem{};
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, solveRcwa(p, {-1, 4, false}));
  }
};

QTEST_GUILESS_MAIN(TestRcwa)

}  // namespace tst_rcwa
#include "tst_rcwa.moc"
