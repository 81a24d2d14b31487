// The schematic eye off its axis (model/physics/eye_oblique_focus.h): the Coddington pencil
// against the paraxial eye on axis, against mirror symmetry, against the quadratic growth of
// oblique astigmatism at small angles, and against an independent finite ray trace (3-D,
// written here from Snell's law and the conic's implicit equation) of neighbouring rays.
#include <QtTest>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <optional>

#include "model/physics/eye_oblique_focus.h"
#include "model/physics/schematic_eye.h"
#include "model/units.h"

namespace tst_eye_oblique_focus {

using namespace fovea;
using V3 = Eigen::Vector3d;  // (x, y, z): z from the corneal vertex to the retina, y meridional

namespace {

struct Ray {
  V3 p, u;
};

// c (x^2 + y^2 + (1+Q) w^2) - 2 w = 0, w = z - z_v; the root on the vertex branch nearest ahead.
std::optional<Ray> throughConic(const Ray& r, double zv, double radius, double q, double n, double n2) {
  const double c = 1.0 / radius, k1 = 1.0 + q;
  const V3 p(r.p.x(), r.p.y(), r.p.z() - zv);
  const double a = c * (r.u.x() * r.u.x() + r.u.y() * r.u.y() + k1 * r.u.z() * r.u.z());
  const double b = 2 * c * (p.x() * r.u.x() + p.y() * r.u.y() + k1 * p.z() * r.u.z()) - 2 * r.u.z();
  const double k = c * (p.x() * p.x() + p.y() * p.y() + k1 * p.z() * p.z()) - 2 * p.z();
  const double disc = b * b - 4 * a * k;
  if (disc < 0) return std::nullopt;
  double t = 1e300;
  for (double s : {(-b - std::sqrt(disc)) / (2 * a), (-b + std::sqrt(disc)) / (2 * a)}) {
    const V3 h = p + s * r.u;
    const double rho2 = h.x() * h.x() + h.y() * h.y();
    const double sag = c * rho2 / (1 + std::sqrt(1 - k1 * c * c * rho2));
    if (s > 0 && s < t && std::abs(h.z() - sag) < 1e-7) t = s;
  }
  if (t > 1e299) return std::nullopt;
  const V3 h = p + t * r.u;
  V3 nrm = V3(2 * c * h.x(), 2 * c * h.y(), 2 * c * k1 * h.z() - 2).normalized();
  if (nrm.dot(r.u) < 0) nrm = -nrm;
  // Snell: the tangential component of n u is kept.
  const double eta = n / n2, ci = nrm.dot(r.u), co = std::sqrt(1 - eta * eta * (1 - ci * ci));
  return Ray{V3(h.x(), h.y(), h.z() + zv), (eta * r.u + (co - eta * ci) * nrm).normalized()};
}

std::optional<Ray> throughEye(const SchematicEyeState& eye, Ray r) {
  const NavarroSurfaces s = navarroSurfaces(eye.lens_parameter_d);
  const double z[4] = {0.0, s.t[0], s.t[0] + s.t[1], s.t[0] + s.t[1] + s.t[2]};
  const double n[5] = {1.0, s.n[0], s.n[1], s.n[2], s.n[3]};
  for (int i = 0; i < 4; ++i) {
    const auto o = throughConic(r, z[i], s.R[i], s.Q[i], n[i], n[i + 1]);
    if (!o) return std::nullopt;
    r = *o;
  }
  return r;
}

}  // namespace

class TestEyeObliqueFocus : public QObject {
  Q_OBJECT
 private slots:
  void onAxisItIsTheParaxialEye() {
    for (double acc : {0.0, 1.25, 3.0}) {
      const EyeObliqueFocus f = eyeObliqueFocus(navarroEye(acc), 0.0);
      QVERIFY(f.valid);
      QVERIFY2(std::abs(f.axis_d + acc) < 1e-6, qPrintable(QString::number(f.axis_d)));
      QVERIFY(std::abs(f.tangential_d - f.axis_d) < 1e-9 && std::abs(f.sagittal_d - f.axis_d) < 1e-9);
      QCOMPARE(f.astigmatism_d, 0.0);
    }
  }

  void mirrorFieldsAreTheSame() {
    const SchematicEyeState eye = navarroEye(1.25);
    const ChiefRayFoci a = navarroChiefRayFoci(eye, 25.0, -1.25), b = navarroChiefRayFoci(eye, -25.0, -1.25);
    QVERIFY(a.valid && b.valid);
    QVERIFY(std::abs(a.pupil_height_mm + b.pupil_height_mm) < 1e-12);
    QVERIFY(std::abs(a.tangential_mm - b.tangential_mm) < 1e-9);
    QVERIFY(std::abs(a.sagittal_mm - b.sagittal_mm) < 1e-9);
    QVERIFY(std::abs(a.retina_mm - b.retina_mm) < 1e-9);
    // The real chief ray is off the paraxial entrance-pupil centre (pupil aberration).
    QVERIFY(std::abs(a.pupil_height_mm) > 1e-4);
  }

  // Seidel: oblique astigmatism and field curvature grow as theta^2 near the axis.
  void astigmatismGrowsAsTheSquareOfTheFieldNearTheAxis() {
    const SchematicEyeState eye = navarroEye(0.0);
    const EyeObliqueFocus a = eyeObliqueFocus(eye, 2.0), b = eyeObliqueFocus(eye, 4.0);
    QVERIFY(a.valid && b.valid && a.astigmatism_d > 0);
    const double ratio = b.astigmatism_d / a.astigmatism_d;
    QVERIFY2(std::abs(ratio - 4.0) < 0.05, qPrintable(QString::number(ratio)));
    // The mean of the two (Petzval-like field curvature against the retina's); the tangential
    // power alone is a small difference of two such terms, so its quartic part shows sooner.
    const double rm = (b.power_tangential_d + b.power_sagittal_d) / (a.power_tangential_d + a.power_sagittal_d);
    QVERIFY2(std::abs(rm - 4.0) < 0.05, qPrintable(QString::number(rm)));
  }

  // The pencil's foci against neighbouring real rays from the same object point: tangential
  // rays offset in the meridional plane cross each other at the tangential focus; a sagittal
  // ray offset normal to it crosses the meridional plane at the sagittal focus.
  // The same for a beam that enters off the pupil centre (pupil offsets 1.5 and -2 mm; theta 0:
  // the zonal pencil).
  void coddingtonFociMatchAFiniteRayTrace_data() {
    QTest::addColumn<double>("pupil_offset");
    QTest::newRow("chief ray") << 0.0;
    QTest::newRow("offset +1.5 mm") << 1.5;
    QTest::newRow("offset -2 mm") << -2.0;
  }
  void coddingtonFociMatchAFiniteRayTrace() {
    QFETCH(double, pupil_offset);
    for (double acc : {0.0, 2.0}) {
      const SchematicEyeState eye = navarroEye(acc);
      for (double theta : {0.0, 10.0, 30.0, 45.0}) {
        if (theta == 0.0 && pupil_offset == 0.0) continue;  // the axis: no pencil to compare off it
        const double v_d = -acc;                            // in focus on axis
        const ChiefRayFoci f = navarroChiefRayFoci(eye, theta, v_d, pupil_offset);
        QVERIFY(f.valid);
        const double th = theta * kDeg;
        const V3 u(0, std::sin(th), std::cos(th));
        const V3 pupil(0, f.pupil_height_mm, eye.entrance_pupil_mm);
        const double delta = 2e-4;  // mm at the pupil crossing
        auto launch = [&](const V3& offset) {
          // From the object point (1/V along the chief ray from the pupil crossing), or parallel.
          if (v_d == 0) return Ray{pupil + offset - 30.0 * u, u};
          const V3 object = pupil + (1000.0 / v_d) * u;
          const V3 dir = (pupil + offset - object).normalized();
          return Ray{object, dir};
        };
        const V3 tn = V3(0, std::cos(th), -std::sin(th));  // in the meridional plane, normal to u
        const auto chief = throughEye(eye, launch(V3::Zero()));
        const auto up = throughEye(eye, launch(delta * tn)), down = throughEye(eye, launch(-delta * tn));
        const auto side = throughEye(eye, launch(V3(delta, 0, 0)));
        QVERIFY(chief && up && down && side);
        // The same chief ray as the model's.
        QVERIFY2(std::abs(chief->p.y() - f.last_hit_y_mm) < 1e-9 && std::abs(chief->p.z() - f.last_hit_z_mm) < 1e-9,
                 qPrintable(QString("%1 %2").arg(chief->p.y()).arg(f.last_hit_y_mm)));
        // Tangential: the two meridional rays' crossing (2-D lines in y-z), projected on the chief ray.
        const Eigen::Vector2d p1(up->p.y(), up->p.z()), d1(up->u.y(), up->u.z());
        const Eigen::Vector2d p2(down->p.y(), down->p.z()), d2(down->u.y(), down->u.z());
        Eigen::Matrix2d m;
        m << d1, -d2;
        const Eigen::Vector2d st = m.colPivHouseholderQr().solve(p2 - p1);
        const Eigen::Vector2d cross = p1 + st[0] * d1;
        const double t_focus =
            (cross - Eigen::Vector2d(chief->p.y(), chief->p.z())).dot(Eigen::Vector2d(chief->u.y(), chief->u.z()));
        // Sagittal: where the offset ray meets x = 0.
        const double s_par = -side->p.x() / side->u.x();
        const V3 meet = side->p + s_par * side->u;
        const double s_focus = (meet - chief->p).dot(chief->u);
        const QString what = QString(
                                 "offset %8 mm, A %1 D, theta %2: tangential %3 vs %4 mm, sagittal %5 vs %6 mm, "
                                 "retina %7 mm")
                                 .arg(acc)
                                 .arg(theta)
                                 .arg(f.tangential_mm, 0, 'f', 5)
                                 .arg(t_focus, 0, 'f', 5)
                                 .arg(f.sagittal_mm, 0, 'f', 5)
                                 .arg(s_focus, 0, 'f', 5)
                                 .arg(f.retina_mm, 0, 'f', 4)
                                 .arg(pupil_offset);
        qInfo("%s", qPrintable(what));
        // docs/physics.md: "the same tangential and sagittal foci, to 1e-5 mm".
        QVERIFY2(std::abs(f.tangential_mm - t_focus) < 1e-5, qPrintable(what));
        QVERIFY2(std::abs(f.sagittal_mm - s_focus) < 1e-5, qPrintable(what));
      }
    }
  }

  // The pencils' foci by themselves: at 30 deg the tangential focus lies in front of the
  // sagittal one (the eye's oblique astigmatism: tangential power the larger), and both powers
  // are expressed as a lens at the pupil that the paraxial eye + that lens focuses the same.
  void theObliqueFocusIsConsistentWithItsPencil() {
    const SchematicEyeState eye = navarroEye(0.0);
    const EyeObliqueFocus o = eyeObliqueFocus(eye, 30.0);
    QVERIFY(o.valid);
    QVERIFY(o.power_tangential_d > o.power_sagittal_d);
    for (auto [v, which] : {std::pair{o.tangential_d, 0}, std::pair{o.sagittal_d, 1}}) {
      const ChiefRayFoci f = navarroChiefRayFoci(eye, 30.0, v);
      const double d = which == 0 ? f.tangential_mm : f.sagittal_mm;
      QVERIFY2(std::abs(d - f.retina_mm) < 1e-6, qPrintable(QString("%1 vs %2").arg(d).arg(f.retina_mm)));
    }
    // docs/physics.md prints these to 0.01 D (the relaxed eye).
    const std::pair<double, double> printed[] = {{10, 0.20}, {20, 0.84}, {30, 2.00}, {40, 3.86}, {50, 6.77}};
    for (auto [theta, astig] : printed) {
      const EyeObliqueFocus e = eyeObliqueFocus(eye, theta);
      qInfo("theta %4.0f deg: P_t %+.3f D, P_s %+.3f D, astigmatism %.3f D", theta, e.power_tangential_d,
            e.power_sagittal_d, e.astigmatism_d);
      QVERIFY2(std::abs(e.astigmatism_d - astig) <= 0.005, qPrintable(QString::number(e.astigmatism_d)));
    }
    QVERIFY(std::abs(o.power_tangential_d - 0.37) <= 0.005 && std::abs(o.power_sagittal_d + 1.63) <= 0.005);
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, eyeObliqueFocus(eye, 61.0));
  }

  // A beam entering h off the pupil centre on the axis: the zonal pencil of the eye's spherical
  // aberration. Seidel: W = W040 (x^2 + y^2)^2 curves 12 W040 h^2 radially (tangential) and
  // 4 W040 h^2 across (sagittal) at (0, h), so for small h P_t / P_s -> 3 and both grow as h^2;
  // +h and -h, and (theta, h) and (-theta, -h), are mirror images.
  void aDecentredBeamSeesTheZonalSphericalAberration() {
    const SchematicEyeState eye = navarroEye(0.0);
    const EyeObliqueFocus a = eyeObliqueFocus(eye, 0.0, 0.25), b = eyeObliqueFocus(eye, 0.0, 0.5);
    QVERIFY(a.valid && b.valid);
    QVERIFY(a.power_tangential_d > 0 && a.power_sagittal_d > 0);  // positive spherical aberration
    const double ratio_ts = a.power_tangential_d / a.power_sagittal_d;
    const double growth = b.power_sagittal_d / a.power_sagittal_d;
    qInfo("h 0.25 mm: P_t %.5f D, P_s %.5f D (ratio %.3f); P_s(0.5) / P_s(0.25) = %.3f", a.power_tangential_d,
          a.power_sagittal_d, ratio_ts, growth);
    QVERIFY2(std::abs(ratio_ts - 3.0) < 0.05, qPrintable(QString::number(ratio_ts)));
    QVERIFY2(std::abs(growth - 4.0) < 0.05, qPrintable(QString::number(growth)));
    const EyeObliqueFocus m = eyeObliqueFocus(eye, 0.0, -0.5);
    QVERIFY(std::abs(m.power_tangential_d - b.power_tangential_d) < 1e-9);
    const EyeObliqueFocus p = eyeObliqueFocus(eye, 20.0, 1.0), q = eyeObliqueFocus(eye, -20.0, -1.0);
    QVERIFY(std::abs(p.power_tangential_d - q.power_tangential_d) < 1e-9);
    QVERIFY(std::abs(p.power_sagittal_d - q.power_sagittal_d) < 1e-9);
    // Decentring changes the pencil off the axis too (the chief ray's value is another number).
    QVERIFY(std::abs(p.power_tangential_d - eyeObliqueFocus(eye, 20.0).power_tangential_d) > 1e-3);
    // docs/physics.md prints these (relaxed eye, on the axis and at 20 deg).
    for (double h : {1.0, 2.0, 3.0}) {
      const EyeObliqueFocus z = eyeObliqueFocus(eye, 0.0, h), o = eyeObliqueFocus(eye, 20.0, h);
      qInfo("h %.0f mm: on axis P_t %+.3f P_s %+.3f D; at 20 deg P_t %+.3f P_s %+.3f D (chief ray %+.3f %+.3f)", h,
            z.power_tangential_d, z.power_sagittal_d, o.power_tangential_d, o.power_sagittal_d,
            eyeObliqueFocus(eye, 20.0).power_tangential_d, eyeObliqueFocus(eye, 20.0).power_sagittal_d);
    }
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, eyeObliqueFocus(eye, 0.0, 4.5));
  }

  // The 2 x 2 power of a decentred beam: the traced meridional values where the offset is
  // meridional; on the axis, the zonal pencil rotated with the offset (rotational symmetry:
  // P = a r r^T + b (I - r r^T)); the cross term odd in the sagittal offset.
  void aSkewOffsetRotatesTheZonalPencil() {
    const SchematicEyeState eye = navarroEye(1.0);
    for (double theta : {0.0, 25.0}) {
      const EyeObliqueFocus plus = eyeObliqueFocus(eye, theta, 1.5), minus = eyeObliqueFocus(eye, theta, -1.5);
      const EyePencilPower a = eyePencilPower(eye, theta, 1.5, 0.0), b = eyePencilPower(eye, theta, -1.5, 0.0);
      QVERIFY(a.valid && b.valid);
      QVERIFY(std::abs(a.meridional_d - plus.power_tangential_d) < 1e-9);
      QVERIFY(std::abs(a.sagittal_d - plus.power_sagittal_d) < 1e-9);
      QVERIFY(std::abs(b.meridional_d - minus.power_tangential_d) < 1e-9);
      QCOMPARE(a.cross_d, 0.0);
      const EyePencilPower up = eyePencilPower(eye, theta, 0.6, 0.8), down = eyePencilPower(eye, theta, 0.6, -0.8);
      QVERIFY(std::abs(up.meridional_d - down.meridional_d) < 1e-12);
      QVERIFY(std::abs(up.cross_d + down.cross_d) < 1e-12);
      QVERIFY(std::abs(up.cross_d) > 1e-3);
    }
    // On the axis: an offset of 1 mm at 40 deg from the meridional direction.
    const EyeObliqueFocus zonal = eyeObliqueFocus(eye, 0.0, 1.0);
    const double phi = 40 * kDeg, c = std::cos(phi), sn = std::sin(phi);
    const EyePencilPower r = eyePencilPower(eye, 0.0, c, sn);
    const double pa = zonal.power_tangential_d, pb = zonal.power_sagittal_d;
    QVERIFY(std::abs(r.meridional_d - (pa * c * c + pb * sn * sn)) < 1e-9);
    QVERIFY(std::abs(r.sagittal_d - (pa * sn * sn + pb * c * c)) < 1e-9);
    QVERIFY(std::abs(r.cross_d - (pa - pb) * c * sn) < 1e-9);
  }
};

QTEST_GUILESS_MAIN(TestEyeObliqueFocus)

}  // namespace tst_eye_oblique_focus
#include "tst_eye_oblique_focus.moc"
