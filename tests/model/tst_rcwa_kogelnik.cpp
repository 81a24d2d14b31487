// RCWA against Kogelnik's closed forms in their validity region (thick, weak gratings:
// ρ = λ²/(Λ² n0 n1) ≫ 1), index-matched cover and substrate (n_c = n_s = n0) so that the
// only difference is the two-wave, slowly-varying-envelope approximation.
#include <QtTest>

#include <cmath>

#include "model/rigorous/rcwa.h"
#include "model/units.h"

namespace tst_rcwa_kogelnik {

using namespace fovea::rigorous;
using fovea::degToRad;
using fovea::kPi;

namespace {

// Kogelnik (Bell Syst. Tech. J. 48, 2909 (1969)), lossless, s polarisation (p: κ → κ ρ̂·σ̂):
//   c_R = cos θ, c_S = cos θ − (λ/(n0 Λ)) cos φ, ϑ = K cos(φ − θ) − K² λ/(4π n0),
//   ν = π n1 d/(λ √|c_R c_S|), ξ = ϑ d/(2 |c_S|);
//   transmission (c_S > 0): η = sin²√(ν²+ξ²)/(1 + ξ²/ν²)                        (Eq. 43)
//   reflection   (c_S < 0): η = 1/(1 + (1 − ξ²/ν²)/sinh²√(ν²−ξ²))  (sin for ξ > ν) (Eq. 56)
struct Kog {
  double eta, nu, xi;
  bool reflection;
};
Kog kogelnik(double n0, double n1, double d_um, double period_nm, double slant_deg, double theta_deg, double lambda_nm,
             bool te) {
  const double lam = lambda_nm * 1e-3, L = period_nm * 1e-3, K = 2 * kPi / L;
  const double th = degToRad(theta_deg), ph = degToRad(slant_deg);
  const double cr = std::cos(th), cs = std::cos(th) - lam / (n0 * L) * std::cos(ph);
  const double vt = K * std::cos(ph - th) - K * K * lam / (4 * kPi * n0);
  // p: coupling reduced by ρ̂·σ̂ (σ = ρ − K direction).
  double pf = 1.0;
  if (!te) {
    const double beta = 2 * kPi * n0 / lam;
    const double rx = beta * std::sin(th), rz = beta * std::cos(th);
    const double sx = rx - K * std::sin(ph), sz = rz - K * std::cos(ph);
    pf = std::abs((rx * sx + rz * sz) / (beta * std::hypot(sx, sz)));
  }
  const double nu = kPi * n1 * pf * d_um / (lam * std::sqrt(std::abs(cr * cs)));
  const double xi = std::abs(vt) * d_um / (2 * std::abs(cs));
  if (cs > 0) {
    const double s = std::sqrt(nu * nu + xi * xi);
    return {std::pow(std::sin(s), 2) / (1 + xi * xi / (nu * nu)), nu, xi, false};
  }
  const double q = nu * nu - xi * xi;
  double denom;
  if (q > 0)
    denom = 1 + (1 - xi * xi / (nu * nu)) / std::pow(std::sinh(std::sqrt(q)), 2);
  else if (q < 0)
    denom = 1 + (xi * xi / (nu * nu) - 1) / std::pow(std::sin(std::sqrt(-q)), 2);  // sinh(i s)² = −sin² s
  else
    denom = 1 + 1 / (nu * nu);
  return {1 / denom, nu, xi, true};
}

RcwaProblem matched(double n0, double n1, double d, double period, double slant, double theta, double lambda, bool te) {
  RcwaProblem p;
  p.n0 = n0;
  p.n1 = n1;
  p.thickness_um = d;
  p.period_nm = period;
  p.slant_deg = slant;
  p.wavelength_nm = lambda;
  p.n_cover = p.n_substrate = n0;
  p.polarization = te ? RcwaPolarization::TE : RcwaPolarization::TM;
  p.setFilmAngleDeg(theta);
  return p;
}
// Slices for ~64 per fringe period along z (staircase error well below 1e-3 here).
int slicesFor(const RcwaProblem& p) {
  const double lz = p.period_nm * 1e-3 / std::max(1e-9, std::abs(std::cos(degToRad(p.slant_deg))));
  return std::max(1, int(std::ceil(64.0 * p.thickness_um / lz)));
}
// Kogelnik's diffracted wave in RCWA: order +1 (order 0 reflected when K_x = 0).
double rcwaDiffracted(const RcwaProblem& p, bool reflection, int orders = 4) {
  const RcwaResult r = solveRcwa(p, {orders, slicesFor(p), false});
  if (r.laterally_uniform) return r.efficiency(0, true);
  return r.efficiency(1, reflection);
}
}  // namespace

class TestRcwaKogelnik : public QObject {
  Q_OBJECT
 private slots:
  // d = 20 µm, n1 = 0.005, λ = 532 nm, Λ = 500 nm, unslanted, on Bragg: η = sin²ν.
  void transmissionOnBragg() {
    const double n0 = 1.5, lam = 532, L = 500;
    const double thetaB = std::asin(lam / (2 * n0 * L)) * 180 / kPi;
    for (bool te : {true, false}) {
      const Kog k = kogelnik(n0, 0.005, 20, L, 90, thetaB, lam, te);
      QVERIFY(k.xi < 1e-9 && !k.reflection);
      const double closed = std::pow(std::sin(k.nu), 2);
      QVERIFY(std::abs(closed - k.eta) < 1e-12);
      const double eta = rcwaDiffracted(matched(n0, 0.005, 20, L, 90, thetaB, lam, te), false);
      QVERIFY2(std::abs(eta - closed) < 1e-2,
               qPrintable(QString("te %1: rcwa %2 kogelnik %3").arg(te).arg(eta).arg(closed)));
    }
    // ν = π/2: full conversion (Kogelnik 100 %), RCWA within 1e-2.
    const double cosB = std::cos(degToRad(thetaB));
    const double d_full = 0.5 * lam * 1e-3 * cosB / 0.005;  // ν = π n1 d/(λ cos θ) = π/2
    const double eta = rcwaDiffracted(matched(n0, 0.005, d_full, L, 90, thetaB, lam, true), false);
    QVERIFY2(std::abs(eta - 1.0) < 1e-2, qPrintable(QString::number(eta)));
  }

  // Unslanted reflection grating at normal incidence on Bragg: η = tanh²ν (a 1-D stack in RCWA).
  void reflectionOnBragg() {
    const double n0 = 1.5, lam = 532, L = lam / (2 * n0);
    for (double d : {5.0, 20.0}) {
      const Kog k = kogelnik(n0, 0.005, d, L, 0, 0, lam, true);
      const double closed = std::pow(std::tanh(k.nu), 2);
      QVERIFY(k.reflection && std::abs(closed - k.eta) < 1e-12);
      const double eta = rcwaDiffracted(matched(n0, 0.005, d, L, 0, 0, lam, true), true);
      QVERIFY2(std::abs(eta - closed) < 1e-2,
               qPrintable(QString("d %1: rcwa %2 kogelnik %3").arg(d).arg(eta).arg(closed)));
    }
  }

  // Slanted gratings off Bragg, s and p: the selectivity curves agree point by point.
  void slantedSelectivity_data() {
    QTest::addColumn<double>("slant");
    QTest::addColumn<double>("thetaB");
    QTest::addColumn<bool>("te");
    QTest::addColumn<double>("d");
    QTest::newRow("transmission 70deg s") << 70.0 << 10.0 << true << 15.0;
    QTest::newRow("transmission 70deg p") << 70.0 << 10.0 << false << 30.0;  // p coupling × cos 120°
    QTest::newRow("reflection 25deg s") << 25.0 << 5.0 << true << 15.0;
    QTest::newRow("reflection 25deg p") << 25.0 << 5.0 << false << 30.0;
  }
  void slantedSelectivity() {
    QFETCH(double, slant);
    QFETCH(double, thetaB);
    QFETCH(bool, te);
    QFETCH(double, d);
    const double n0 = 1.5, n1 = 0.005, lam = 532;
    const double L = lam / (2 * n0 * std::cos(degToRad(slant - thetaB)));  // Bragg at θ_B
    double worst = 0, peak = 0;
    for (double dth : {-0.6, -0.3, -0.1, 0.0, 0.1, 0.3, 0.6}) {
      const Kog k = kogelnik(n0, n1, d, L, slant, thetaB + dth, lam, te);
      const double eta = rcwaDiffracted(matched(n0, n1, d, L, slant, thetaB + dth, lam, te), k.reflection);
      worst = std::max(worst, std::abs(eta - k.eta));
      peak = std::max(peak, k.eta);
    }
    QVERIFY(peak > 0.2);  // a real grating, not a null comparison
    QVERIFY2(worst < 1e-2, qPrintable(QString("worst |Δη| %1").arg(worst)));
  }

  // Outside the validity region (thin, strong: ρ ~ 1) Kogelnik must visibly fail: several
  // orders carry power and the two-wave result is off — the comparison can fail.
  void kogelnikFailsWhenRhoSmall() {
    const double n0 = 1.5, n1 = 0.05, lam = 532, L = 3000, d = 4;
    const double thetaB = std::asin(lam / (2 * n0 * L)) * 180 / kPi;
    const double rho = std::pow(lam / L, 2) / (n0 * n1);
    QVERIFY(rho < 1.0);
    const Kog k = kogelnik(n0, n1, d, L, 90, thetaB, lam, true);
    const RcwaResult r = solveRcwa(matched(n0, n1, d, L, 90, thetaB, lam, true), {12, 1, false});
    QVERIFY(std::abs(r.total_efficiency - 1.0) < 1e-10);
    QVERIFY(r.efficiency(-1, false) > 0.02 || r.efficiency(2, false) > 0.02);  // Raman–Nath orders
    QVERIFY(std::abs(r.efficiency(1, false) - k.eta) > 0.05);
  }
};

QTEST_GUILESS_MAIN(TestRcwaKogelnik)

}  // namespace tst_rcwa_kogelnik
#include "tst_rcwa_kogelnik.moc"
