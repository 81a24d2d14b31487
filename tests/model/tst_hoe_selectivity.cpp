// Angular and spectral selectivity of recorded HOE layers against closed forms: Kogelnik's
// on-Bragg reflection efficiency tanh^2(pi n1 d / lambda) at normal incidence, the Bragg
// wavelength moved by shrinkage and by a mean-index change, the symmetry of the on-axis
// geometry, and the half-maximum width of a known curve.
#include <QtTest>

#include <cmath>
#include <numbers>

#include "app/embedded_scene.h"
#include "model/analysis/hoe_selectivity.h"

namespace tst_hoe_selectivity {

using namespace fovea;

namespace {

// A single-layer reflection HOE recorded and probed on its normal: the projector (reference)
// 70 mm and the signal focus 22 mm in front of the plate, both on the axis.
Scene onAxisScene(double shrinkage_percent = 0.0, double n0_delta = 0.0) {
  Scene s;
  s.projector.pose.position_mm = {0.0, 0.0, -70.0};
  s.projector.wavelengths_nm = {532.0};
  HoeLayer l;
  l.name = "green";
  l.thickness_um = 16.0;
  l.n0 = 1.5;
  l.n1 = 0.015;
  l.shrinkage_percent = shrinkage_percent;
  l.recording_n0_delta = n0_delta;
  l.recording.wavelength_nm = 532.0;
  l.recording.reference_point_mm = {0.0, 0.0, -70.0};
  l.recording.signal_point_mm = {0.0, 0.0, -22.0};
  s.hoe_layers = {l};
  return s;
}

// Wavelength where Kogelnik's dephasing xi changes sign (linear interpolation).
double braggWavelength(const LayerSelectivity& l) {
  for (std::size_t i = 1; i < l.spectrum.size(); ++i) {
    const auto &a = l.spectrum[i - 1], &b = l.spectrum[i];
    if ((a.xi <= 0) != (b.xi <= 0)) return a.x + (0 - a.xi) / (b.xi - a.xi) * (b.x - a.x);
  }
  return NAN;
}

}  // namespace

class TestHoeSelectivity : public QObject {
  Q_OBJECT
 private slots:
  void onBraggReflectionIsTanhSquared() {
    const Scene s = onAxisScene();
    SelectivityOptions o;
    o.polarization = Polarization::S;
    const SelectivityResult r = analyzeSelectivity(s, o);
    QCOMPARE(r.layers.size(), std::size_t(1));
    const LayerSelectivity& l = r.layers[0];
    QVERIFY(l.valid);
    QCOMPARE(l.probe_wavelength_nm, 532.0);
    QVERIFY(std::abs(l.incidence_deg) < 1e-9);
    QVERIFY(std::abs(l.nominal_xi) < 1e-9);
    const double nu = std::numbers::pi * 0.015 * 16.0 / 0.532;  // pi n1 d / lambda, c_R = -c_S = 1
    QVERIFY2(std::abs(l.nominal_efficiency - std::pow(std::tanh(nu), 2)) < 1e-9,
             qPrintable(QString::number(l.nominal_efficiency, 'g', 12)));
    // At normal incidence s and p see the same coupling: unpolarised is the same number.
    o.polarization = Polarization::Unpolarized;
    QVERIFY(std::abs(analyzeSelectivity(s, o).layers[0].nominal_efficiency - l.nominal_efficiency) < 1e-12);
  }

  void onAxisAngularCurveIsSymmetric() {
    SelectivityOptions o;
    o.angle_samples = 201;
    o.angle_span_deg = 30.0;  // at normal incidence the angular selectivity is broad (xi ~ detuning^2)
    const LayerSelectivity l = analyzeSelectivity(onAxisScene(), o).layers[0];
    QCOMPARE(l.angle.size(), std::size_t(201));
    for (std::size_t i = 0; i < l.angle.size(); ++i) {
      const auto &a = l.angle[i], &b = l.angle[l.angle.size() - 1 - i];
      QVERIFY(std::abs(a.x + b.x) < 1e-12);
      QVERIFY2(std::abs(a.efficiency - b.efficiency) < 1e-12, qPrintable(QString::number(a.x)));
    }
    // The peak sits at zero detuning, and the curve falls to half on both sides.
    QVERIFY(std::abs(l.peak_detuning_deg) < 1e-9);
    QVERIFY(l.angular_fwhm_deg.has_value());
  }

  void angularCurveFollowsKogelnikEq56() {
    // Unslanted reflection grating (K = 2 beta along the normal) probed at outside angle delta:
    // inside theta = asin(sin delta / n0), c_R = cos theta, c_S = cos theta - 2,
    // vartheta = K cos theta - K^2 / (2 beta) = -2 beta (1 - cos theta) (Kogelnik Eqs. 17, 23, 24),
    // nu = pi n1 d / (lambda sqrt(c_R |c_S|)), xi = |vartheta| d / (2 |c_S|), s polarisation, and
    // eta = 1 / (1 + (1 - xi^2/nu^2) / sinh^2 sqrt(nu^2 - xi^2))  (Eq. 56; sin past xi = nu).
    SelectivityOptions o;
    o.polarization = Polarization::S;
    o.angle_span_deg = 30.0;
    o.angle_samples = 61;
    const LayerSelectivity l = analyzeSelectivity(onAxisScene(), o).layers[0];
    const double n0 = 1.5, n1 = 0.015, d = 16.0, lambda = 0.532;
    const double beta = 2.0 * std::numbers::pi * n0 / lambda;
    for (const auto& s : l.angle) {
      const double theta = std::asin(std::sin(s.x * std::numbers::pi / 180.0) / n0);
      const double c_r = std::cos(theta), c_s = std::cos(theta) - 2.0;
      const double vartheta = -2.0 * beta * (1.0 - std::cos(theta));
      const double nu = std::numbers::pi * n1 * d / (lambda * std::sqrt(c_r * std::abs(c_s)));
      const double xi = std::abs(vartheta) * d / (2.0 * std::abs(c_s));
      const double g2 = nu * nu - xi * xi;
      const double sh2 = g2 >= 0 ? std::pow(std::sinh(std::sqrt(g2)), 2) : -std::pow(std::sin(std::sqrt(-g2)), 2);
      const double eta = 1.0 / (1.0 + (1.0 - xi * xi / (nu * nu)) / sh2);
      QVERIFY2(std::abs(s.efficiency - eta) < 1e-9,
               qPrintable(QString("delta %1: %2 vs %3").arg(s.x).arg(s.efficiency).arg(eta)));
    }
  }

  void shrinkageMovesTheBraggWavelength() {
    // Fringes parallel to the film: K_z -> K_z/(1+s), so lambda_B = lambda_rec (1+s) at
    // normal incidence; a recording index n0 - delta scales it by n0 / (n0 - delta).
    SelectivityOptions o;
    o.wavelength_samples = 2001;
    const double lb0 = braggWavelength(analyzeSelectivity(onAxisScene(), o).layers[0]);
    QVERIFY2(std::abs(lb0 - 532.0) < 1e-3, qPrintable(QString::number(lb0, 'g', 10)));
    const double lb1 = braggWavelength(analyzeSelectivity(onAxisScene(-2.0), o).layers[0]);
    QVERIFY2(std::abs(lb1 - 532.0 * 0.98) < 1e-3, qPrintable(QString::number(lb1, 'g', 10)));
    const double lb2 = braggWavelength(analyzeSelectivity(onAxisScene(0.0, 0.01), o).layers[0]);
    QVERIFY2(std::abs(lb2 - 532.0 * 1.5 / 1.49) < 1e-3, qPrintable(QString::number(lb2, 'g', 10)));
    // The shrunk layer no longer diffracts the 532 nm probe as well as the nominal one.
    const LayerSelectivity shrunk = analyzeSelectivity(onAxisScene(-2.0), o).layers[0];
    QVERIFY(shrunk.nominal_efficiency < 0.5 * shrunk.peak_spectral_efficiency);
  }

  void prototypeLayersAreBraggMatched() {
    const Scene scene = embeddedDefaultScene();
    const SelectivityResult sel = analyzeSelectivity(scene);
    QCOMPARE(sel.layers.size(), scene.hoe_layers.size());
    for (const auto& l : sel.layers) {
      QVERIFY(l.valid);
      // Recorded with the projector as reference and probed by it at the same wavelength.
      QVERIFY2(std::abs(l.nominal_xi) < 1e-6, qPrintable(QString::fromStdString(l.name)));
      QVERIFY(l.nominal_efficiency > 0.3);
      QVERIFY(l.spectral_fwhm_nm.has_value() && l.angular_fwhm_deg.has_value());
    }
  }

  void fullWidthHalfMaxOfAGaussian() {
    std::vector<SelectivitySample> c;
    const double sigma = 1.7;
    for (int i = 0; i <= 4000; ++i) {
      SelectivitySample s;
      s.x = -10.0 + 20.0 * i / 4000;
      s.efficiency = 0.8 * std::exp(-0.5 * s.x * s.x / (sigma * sigma));
      c.push_back(s);
    }
    const auto w = fullWidthHalfMax(c);
    QVERIFY(w.has_value());
    QVERIFY2(std::abs(*w - 2.0 * std::sqrt(2.0 * std::log(2.0)) * sigma) < 1e-4, qPrintable(QString::number(*w)));
    // A curve that never falls to half on one side has no width.
    c.resize(2001);
    for (std::size_t i = 0; i < 1000; ++i) c[i].efficiency = 0.8;
    QVERIFY(!fullWidthHalfMax(c).has_value());
  }
};

QTEST_GUILESS_MAIN(TestHoeSelectivity)

}  // namespace tst_hoe_selectivity
#include "tst_hoe_selectivity.moc"
