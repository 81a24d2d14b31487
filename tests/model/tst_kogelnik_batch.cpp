// The SIMD Kogelnik batch (model/physics/kogelnik_batch.h) against the scalar closed forms
// (kogelnik::lossless): double to 1e-15 absolute on eta, float to its own rounding, over random
// gratings spanning both branches (transmission c_s > 0, reflection c_s < 0), the branch change
// (a = nu^2 - xi^2 through 0), the thin limit (|a| < 1), large phases (the scalar fallback
// beyond 1e6 rad), grazing and invalid inputs. Odd lengths exercise the vector tails.
#include <QtTest>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "model/physics/kogelnik.h"
#include "model/physics/kogelnik_batch.h"

namespace tst_kogelnik_batch {

using namespace fovea;

namespace {
struct Inputs {
  std::vector<double> c_r, c_s, vt, kappa, d;
  void add(double cr, double cs, double v, double k, double dd) {
    c_r.push_back(cr);
    c_s.push_back(cs);
    vt.push_back(v);
    kappa.push_back(k);
    d.push_back(dd);
  }
};

Inputs randomGratings(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Inputs in;
  for (std::size_t i = 0; i < n; ++i) {
    const double cr = std::pow(10.0, -3.0 * u(rng));                            // 1e-3 .. 1
    const double cs = (u(rng) < 0.5 ? -1 : 1) * std::pow(10.0, -3.0 * u(rng));  // both branches
    const double kappa = std::pow(10.0, -4.0 + 3.0 * u(rng));                   // rad/µm
    const double d = std::pow(10.0, -1.0 + 4.0 * u(rng));                       // 0.1 µm .. 1 mm
    const double nu = kappa * d / std::sqrt(cr * std::abs(cs));
    // Dephasing around the branch change for reflection (xi ~ nu) or spread widely.
    const double xi = u(rng) < 0.3 ? nu * (1.0 + 1e-3 * (u(rng) - 0.5)) : std::pow(10.0, -3.0 + 6.0 * u(rng));
    const double vt = (u(rng) < 0.5 ? -1 : 1) * 2.0 * std::abs(cs) * xi / d;  // xi = |vt| d / (2 |c_s|)
    in.add(cr, cs, vt, kappa, d);
  }
  // Edges: invalid, grazing, thin, huge phase (scalar fallback), exact Bragg, exact branch change.
  in.add(0.0, 0.5, 0.0, 0.01, 10);
  in.add(0.5, 0.5, 0.0, 0.01, 0.0);
  in.add(0.5, 1e-13, 0.0, 0.01, 10);
  in.add(0.7, 0.6, 1e-9, 1e-6, 1.0);
  in.add(0.7, 0.6, 2e3, 0.01, 1000);
  in.add(0.7, -0.6, 0.0, 0.01, 20);
  const double nu = 0.01 * 20 / std::sqrt(0.7 * 0.6);
  in.add(0.7, -0.6, 2.0 * 0.6 * nu / 20, 0.01, 20);
  return in;
}
}  // namespace

class TestKogelnikBatch : public QObject {
  Q_OBJECT
 private slots:
  void doubleBatchMatchesScalar() {
    const Inputs in = randomGratings(200001, 7);
    const std::size_t n = in.c_r.size();
    std::vector<double> eta(n);
    kogelnik::losslessBatch(in.c_r.data(), in.c_s.data(), in.vt.data(), in.kappa.data(), in.d.data(), eta.data(), n);
    double worst = 0;
    std::size_t at = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double ref = kogelnik::lossless(in.c_r[i], in.c_s[i], in.vt[i], in.kappa[i], in.d[i]).efficiency;
      QVERIFY(std::isfinite(eta[i]) && eta[i] >= 0.0 && eta[i] <= 1.0);
      if (std::abs(eta[i] - ref) > worst) worst = std::abs(eta[i] - ref), at = i;
    }
    qInfo("SIMD double (%s) vs scalar over %zu gratings: max |d eta| %.3g (at #%zu)", kogelnik::batchInstructionSet(),
          n, worst, at);
    QVERIFY2(worst <= 1e-15, qPrintable(QString::number(worst)));
  }

  void zeroOrderMatchesScalar() {
    // The variant with the zero order (what the trace pipeline's stack passes to the next
    // layer): eta bit for bit the eta-only batch, the zero order within 1e-15 of losslessT's
    // own closed form (cos^2 + xi^2 shc^2 in transmission, 1 / (1 + g^2) in reflection).
    const Inputs in = randomGratings(100001, 11);
    const std::size_t n = in.c_r.size();
    std::vector<double> eta(n), eta_only(n), zero(n);
    kogelnik::losslessBatch(in.c_r.data(), in.c_s.data(), in.vt.data(), in.kappa.data(), in.d.data(), eta.data(),
                            zero.data(), n);
    kogelnik::losslessBatch(in.c_r.data(), in.c_s.data(), in.vt.data(), in.kappa.data(), in.d.data(), eta_only.data(),
                            n);
    double worst = 0, worst_sum = 0;
    int transmission_far = 0;  // transmission with phase u > pi: the cos quadrants are exercised
    for (std::size_t i = 0; i < n; ++i) {
      QCOMPARE(eta[i], eta_only[i]);
      const kogelnik::Result ref = kogelnik::lossless(in.c_r[i], in.c_s[i], in.vt[i], in.kappa[i], in.d[i]);
      QVERIFY(std::isfinite(zero[i]) && zero[i] >= 0.0 && zero[i] <= 1.0);
      worst = std::max(worst, std::abs(zero[i] - ref.zero_order));
      if (ref.reflection) worst_sum = std::max(worst_sum, std::abs(eta[i] + zero[i] - 1.0));  // lossless: no power lost
      if (!ref.reflection && std::hypot(ref.nu, ref.xi) > std::numbers::pi && std::hypot(ref.nu, ref.xi) < 1e6)
        ++transmission_far;
    }
    qInfo("zero order, SIMD double vs scalar over %zu gratings: max |d| %.3g; reflection |eta + zero - 1| %.3g", n,
          worst, worst_sum);
    QVERIFY2(worst <= 1e-15, qPrintable(QString::number(worst)));
    QVERIFY2(worst_sum <= 1e-15, qPrintable(QString::number(worst_sum)));
    QVERIFY(transmission_far > 10000);
  }

  void floatBatchIsFloatAccurate() {
    // Prototype-like gratings (nu and xi up to ~10): float costs ~1e-6 on eta.
    Inputs in;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 10001; ++i) {
      const double cs = (u(rng) < 0.5 ? -1 : 1) * (0.2 + 0.8 * u(rng));
      in.add(0.3 + 0.7 * u(rng), cs, 0.05 * (u(rng) - 0.5), 0.005 + 0.02 * u(rng), 5 + 20 * u(rng));
    }
    const std::size_t n = in.c_r.size();
    std::vector<float> fc_r(n), fc_s(n), fvt(n), fk(n), fd(n), eta(n);
    for (std::size_t i = 0; i < n; ++i) {
      fc_r[i] = float(in.c_r[i]), fc_s[i] = float(in.c_s[i]), fvt[i] = float(in.vt[i]);
      fk[i] = float(in.kappa[i]), fd[i] = float(in.d[i]);
    }
    kogelnik::losslessBatch(fc_r.data(), fc_s.data(), fvt.data(), fk.data(), fd.data(), eta.data(), n);
    double worst = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double ref = kogelnik::lossless(fc_r[i], fc_s[i], fvt[i], fk[i], fd[i]).efficiency;  // same float inputs
      worst = std::max(worst, std::abs(double(eta[i]) - ref));
    }
    qInfo("SIMD float vs scalar double: max |d eta| %.3g", worst);
    QVERIFY2(worst <= 1e-5, qPrintable(QString::number(worst)));
  }
};

QTEST_GUILESS_MAIN(TestKogelnikBatch)

}  // namespace tst_kogelnik_batch
#include "tst_kogelnik_batch.moc"
