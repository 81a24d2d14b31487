#include "app/studio/report_document.h"

#include <QAbstractTextDocumentLayout>
#include <QBuffer>
#include <QFileInfo>
#include <QPageLayout>
#include <QPageSize>
#include <QPainter>
#include <QPdfWriter>
#include <QSaveFile>
#include <QTextDocument>
#include <QUrl>

#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>

#include <cmath>
#include <memory>

#include "app/studio/live_trace_features.h"
#include "app/studio/main_window.h"
#include "app/studio/report_html.h"
#include "app/studio/report_tolerance.h"
#include "app/studio/window_capture.h"
#include "fovea/version.h"
#include "model/json_numbers.h"
#include "model/scene/scene_geometry.h"
#include "viz/scene_view.h"
#include "viz/trace_overlay.h"
#include "widgets/live_trace.h"
#include "widgets/number_text.h"
#include "widgets/plots/plot_builders.h"
#include "widgets/plots/plot_render.h"
#include "widgets/retina_view.h"

namespace fovea::studio {

using widgets::DisplayUnits;
using widgets::PlotData;

using report_html::esc;
using report_html::g;
using report_html::pct;

namespace {

QString vec(const std::array<double, 3>& v, const DisplayUnits& u) {
  return QString("(%1, %2, %3) %4")
      .arg(g(u.lengthFromMm(v[0])), g(u.lengthFromMm(v[1])), g(u.lengthFromMm(v[2])), u.lengthSymbol());
}
QString rot(const std::array<double, 3>& r, const DisplayUnits& u) {
  return QString("(%1, %2, %3) %4")
      .arg(g(u.angleFromDeg(r[0])), g(u.angleFromDeg(r[1])), g(u.angleFromDeg(r[2])), u.angleSymbol());
}
QString gazeText(const std::array<double, 2>& gz, const DisplayUnits& u) {
  return QString("(%1, %2) %3").arg(g(u.angleFromDeg(gz[0])), g(u.angleFromDeg(gz[1])), u.angleSymbol());
}

// The retinal image's options and their figures, for its caption (the preview's Retina image options).
QString retinaImageOptionsText(const ReportRetinaImage& ri) {
  QString t = ri.options.speckle_patterns == 0 ? QString(" Speckle off")
                                               : QString(" Speckle: %1 pattern%2 per laser, %3 grain (seed %4)")
                                                     .arg(ri.options.speckle_patterns)
                                                     .arg(ri.options.speckle_patterns == 1 ? "" : "s")
                                                     .arg(ri.options.speckle_grain_pupil ? "pupil" : "pixel")
                                                     .arg(static_cast<qulonglong>(ri.options.speckle_seed));
  if (ri.speckle_contrast) {
    t += QString(", contrast %1").arg(*ri.speckle_contrast, 0, 'f', 3);
    if (ri.speckle_expected) t += QString(" (expected %1)").arg(*ri.speckle_expected, 0, 'f', 3);
  }
  t += ri.options.per_laser_calibration ? "; each laser warped on its own (per-laser calibration)"
                                        : "; one geometric calibration (the laser nearest 555 nm)";
  if (ri.lateral_colour_arcmin) t += QString(", lateral colour %1 arcmin").arg(*ri.lateral_colour_arcmin, 0, 'f', 1);
  if (ri.options.hoe_shift_mm != std::array<double, 2>{0, 0})
    t += QString("; HOE shifted by x_p (%1, %2) mm")
             .arg(ri.options.hoe_shift_mm[0], 0, 'f', 2)
             .arg(ri.options.hoe_shift_mm[1], 0, 'f', 2);
  return t + ".";
}

QString row(const QString& a, const QString& b) {
  return "<tr><td valign='top'><b>" + a + "</b></td><td>" + b + "</td></tr>";
}
QString row3(const QString& a, const QString& b, const QString& c) {
  return "<tr><td>" + a + "</td><td align='right'><b>" + b + "</b></td><td>" + c + "</td></tr>";
}
const char* kTable = "<table border='1' cellspacing='0' cellpadding='4' width='100%'>";

QString keyNumbersHtml(const ReportData& d, const DisplayUnits& u) {
  QString h = kTable;
  h += "<tr><th align='left'>Quantity</th><th align='right'>Value</th><th align='left'>From</th></tr>";
  for (const GazeTrace& t : d.traces) {
    const auto& f = t.json.value("fov_deg", nlohmann::json::object());
    h += row3("Retinal FOV at gaze " + gazeText(t.gaze_deg, u),
              QString("%1 × %2 %3")
                      .arg(g(u.angleFromDeg(jsonNumber(f, {"horizontal"}))),
                           g(u.angleFromDeg(jsonNumber(f, {"vertical"}))), u.angleSymbol()) +
                  QString(" (diag. %1)").arg(g(u.angleFromDeg(jsonNumber(f, {"diagonal"})))),
              QString("trace: exact FOV (field edges root-found, fov_edges.h; arrival directions, ours), as sweep"));
    QStringList per;
    for (const auto& w : t.json.value("per_wavelength", nlohmann::json::array()))
      per << QString("%1 nm: %2").arg(g(jsonNumber(w, {"wavelength_nm"}))).arg(pct(jsonNumber(w, {"mean_efficiency"})));
    h += row3("Mean efficiency in the pupil at gaze " + gazeText(t.gaze_deg, u),
              pct(jsonNumber(t.json, {"mean_efficiency"})), per.join(", "));
  }
  if (d.sweep.is_object()) {
    const auto& eb = d.sweep.value("eyebox", nlohmann::json::object());
    h += row3(
        "Eye box", u.length(jsonNumber(d.sweep, {"eyebox_mm"})),
        QString("sweep %1 … %2 %3, FOV within %4 %3 of the zero-gaze %5 %3")
            .arg(g(u.angleFromDeg(d.sweep["samples"].empty() ? NAN
                                                             : jsonNumber(d.sweep["samples"].front(), {"gaze_deg"}))),
                 g(u.angleFromDeg(d.sweep["samples"].empty() ? NAN
                                                             : jsonNumber(d.sweep["samples"].back(), {"gaze_deg"}))),
                 u.angleSymbol(), g(u.angleFromDeg(1.0)), g(u.angleFromDeg(jsonNumber(eb, {"reference_fov_deg"})))));
    h += row3("Gaze range of the eye box",
              QString("%1 … %2 %3")
                  .arg(g(u.angleFromDeg(jsonNumberAt(eb, "gaze_range_deg", 0))),
                       g(u.angleFromDeg(jsonNumberAt(eb, "gaze_range_deg", 1))), u.angleSymbol()),
              "sweep (borders bisected)");
    h += row3("HOE travel at the eye-box borders",
              QString("%1 … %2 %3")
                  .arg(g(u.lengthFromMm(jsonNumberAt(eb, "travel_mm", 0))),
                       g(u.lengthFromMm(jsonNumberAt(eb, "travel_mm", 1))), u.lengthSymbol()),
              "sweep: FOV-maximising HOE shift");
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& s : d.sweep.value("samples", nlohmann::json::array())) {
      const double e = jsonNumber(s, {"mean_efficiency"});
      if (std::isfinite(e)) lo = std::min(lo, e), hi = std::max(hi, e);
    }
    h += row3("Mean efficiency over the sweep", pct(lo) + " … " + pct(hi), "sweep, with the optimal HOE shift");
  }
  if (d.resolution.is_object()) {
    double best = NAN, nearest = INFINITY;
    for (const auto& s : d.resolution.value("samples", nlohmann::json::array())) {
      const double e = std::abs(jsonNumber(s, {"eccentricity_deg"}));
      if (e < nearest) nearest = e, best = jsonNumber(s, {"perceived_cpd"});
    }
    h += row3("Perceived resolution at the gaze", g(best) + " cpd", "resolution");
    h += row3("Peripheral field",
              QString("%1 … %2 %3")
                  .arg(g(u.angleFromDeg(jsonNumberAt(d.resolution, "peripheral_field_deg", 0))),
                       g(u.angleFromDeg(jsonNumberAt(d.resolution, "peripheral_field_deg", 1))), u.angleSymbol()),
              QString("%1 of %2 projector columns reach the eye")
                  .arg(g(jsonNumber(d.resolution, {"peripheral_pixel_integral"})),
                       g(jsonNumber(d.resolution, {"pixels_horizontal"}), 6)));
  }
  if (d.selectivity.is_object())
    for (const auto& l : d.selectivity.value("layers", nlohmann::json::array()))
      h += row3(QString("HOE layer %1 at the plate centre").arg(esc(l.value("name", std::string()))),
                pct(jsonNumber(l, {"nominal_efficiency"})),
                QString("%1 nm probe; angular FWHM %2, spectral FWHM %3 nm")
                    .arg(g(jsonNumber(l, {"probe_wavelength_nm"})), u.angle(jsonNumber(l, {"angular_fwhm_deg"}), 3),
                         g(jsonNumber(l, {"spectral_fwhm_nm"}), 3)));
  return h + "</table>";
}

// Both eyes of a binocular scene: each eye's FOV, efficiency and x_p at the chosen gazes.
ReportSection bothEyesSection(const ReportData& d, const DisplayUnits& u) {
  QString h = kTable;
  h += "<tr><th align='left'>Eye</th><th align='left'>Gaze</th><th align='right'>Retinal FOV</th>"
       "<th align='right'>Mean efficiency</th><th align='right'>x_p</th></tr>";
  for (const char* side : {"left", "right"}) {
    const nlohmann::json& eye = d.eyes.value(side, nlohmann::json::object());
    for (const auto& e : eye.value("gazes", nlohmann::json::array())) {
      const auto& f = e.value("fov_deg", nlohmann::json::object());
      const std::array<double, 2> gz{jsonNumberAt(e, "gaze_deg", 0), jsonNumberAt(e, "gaze_deg", 1)};
      h += QString(
               "<tr><td>%1</td><td>%2</td><td align='right'><b>%3 × %4 %5</b> (diag. %6)</td>"
               "<td align='right'>%7</td><td align='right'>(%8, %9) %10</td></tr>")
               .arg(side, gazeText(gz, u), g(u.angleFromDeg(jsonNumber(f, {"horizontal"}))),
                    g(u.angleFromDeg(jsonNumber(f, {"vertical"}))), u.angleSymbol(),
                    g(u.angleFromDeg(jsonNumber(f, {"diagonal"}))), pct(jsonNumber(e, {"mean_efficiency"})),
                    g(u.lengthFromMm(jsonNumberAt(e, "x_p_mm", 0))), g(u.lengthFromMm(jsonNumberAt(e, "x_p_mm", 1))))
               .arg(u.lengthSymbol());
    }
  }
  h += "</table>";
  // Each eye's eye box over the design gaze range (the sweep's HOE-shift eye box per eye).
  QStringList boxes;
  for (const char* side : {"left", "right"}) {
    const nlohmann::json& eye = d.eyes.value(side, nlohmann::json::object());
    if (!eye.contains("eyebox_mm")) continue;
    boxes << QString("%1 eye <b>%2</b>").arg(side, u.length(jsonNumber(eye, {"eyebox_mm"})));
  }
  const QString boxText = boxes.isEmpty()
                              ? QString()
                              : QString(
                                    " Eye box (HOE following the gaze, over the design gaze range, as in the key "
                                    "numbers): %1.")
                                    .arg(boxes.join(", "));
  const bool explicitLeft = d.scene.binocular && d.scene.binocular->left.has_value();
  const QString intro =
      QString(
          "The scene is binocular (IPD %1): its train is the right eye's, the left eye's %2. Each eye traced at "
          "the chosen gazes (a gaze in the bench frame: the same direction for both eyes), with the "
          "FOV-maximising HOE shift x_p of that eye (applied only when the HOE follows the gaze); the rest of "
          "the report is the right eye's.")
          .arg(u.length(d.scene.binocular ? d.scene.binocular->ipd_mm : NAN),
               explicitLeft ? QString("its own train (mode explicit)")
                            : QString("its mirror image about the mid-plane"));
  return ReportSection{"Both eyes", intro + boxText + h, {}};
}

QImage capture3d(viz::SceneView* view) {
  QImage img = view->renderToImage();
  return img.isNull() ? img : opaqueFramebuffer(img);  // colours as on screen (window_capture.h)
}

// Pixels that differ clearly (summed RGB difference above 48 of 765) between two captures.
int changedPixels(const QImage& a, const QImage& b) {
  if (a.size() != b.size()) return 0;
  int n = 0;
  for (int y = 0; y < a.height(); ++y) {
    const auto* pa = reinterpret_cast<const QRgb*>(a.constScanLine(y));
    const auto* pb = reinterpret_cast<const QRgb*>(b.constScanLine(y));
    for (int x = 0; x < a.width(); ++x)
      if (std::abs(qRed(pa[x]) - qRed(pb[x])) + std::abs(qGreen(pa[x]) - qGreen(pb[x])) +
              std::abs(qBlue(pa[x]) - qBlue(pb[x])) >
          48)
        ++n;
  }
  return n;
}

}  // namespace

void addPlotFigure(QList<ReportFigure>& out, const PlotData& p) {
  if (p.isEmpty()) return;
  ReportFigure f;
  f.id = "plot:" + p.id;
  f.caption = p.caption.isEmpty() ? p.title : p.caption;
  f.image = widgets::renderPlotImage(p, QSize(900, 560), 1.6);
  f.tableHtml = p.summaryHtml;
  out << f;
}

int ReportContent::figureCount() const {
  int n = 0;
  for (const auto& s : sections) n += static_cast<int>(s.figures.size());
  return n;
}

QString sceneSummaryTableHtml(const Scene& s, const DisplayUnits& u) {
  QString h = kTable;
  h += "<tr><th align='left'>Element</th><th align='left'>Parameters</th></tr>";
  const auto& p = s.projector;
  QStringList wl;
  for (double w : p.wavelengths_nm) wl << g(w);
  h += row("Projector: " + esc(p.name),
           QString("at %1, rotated %2; %3 × %4 px over %5 × %6 %7; lasers %8 nm; exit pupil %9")
               .arg(vec(p.pose.position_mm, u), rot(p.pose.rotation_deg, u))
               .arg(p.pixels[0])
               .arg(p.pixels[1])
               .arg(g(u.angleFromDeg(p.fov_deg[0])), g(u.angleFromDeg(p.fov_deg[1])), u.angleSymbol(), wl.join(", "),
                    u.length(p.exit_pupil_diameter_mm)));
  h += row("HOE: " + esc(s.hoe.name),
           QString("at %1, rotated %2; %3 × %4; cover index %5, substrate index %6")
               .arg(vec(s.hoe.pose.position_mm, u), rot(s.hoe.pose.rotation_deg, u), u.length(s.hoe.size_mm[0]),
                    u.length(s.hoe.size_mm[1]), g(s.hoe.cover_index), g(s.hoe.substrate_index)));
  for (const HoeLayer& l : s.hoe_layers)
    h += row("HOE layer: " + esc(l.name),
             QString("d = %1 µm, n0 = %2, n1 = %3, recorded at %4 nm%5; shrinkage %6 %, Δn0 %7")
                 .arg(g(l.thickness_um), g(l.n0), g(l.n1), g(l.recording.wavelength_nm),
                      l.recording.phase_conjugate ? " (phase-conjugate)" : "", g(l.shrinkage_percent),
                      g(l.recording_n0_delta)));
  const Eye& e = s.eye;
  h += row("Eye", QString("relief %1, pupil Ø %2, eyeball Ø %3; gaze %4, design range %5 … %6 %7")
                      .arg(u.length(e.relief_mm), u.length(e.pupil_diameter_mm), u.length(e.eyeball_diameter_mm),
                           gazeText(e.gaze_deg, u), g(u.angleFromDeg(e.gaze_range_deg[0])),
                           g(u.angleFromDeg(e.gaze_range_deg[1])), u.angleSymbol()));
  const FovealDisplay& f = s.foveal_display;
  h += row("Foveal display: " + esc(f.name),
           QString("at %1; %2 × %3 active, %4 × %5 px; combiner %6: M = %7, image at %8")
               .arg(vec(f.pose.position_mm, u), u.length(f.size_mm[0]), u.length(f.size_mm[1]))
               .arg(f.pixels[0])
               .arg(f.pixels[1])
               .arg(esc(f.combiner.name), g(f.combiner.magnification), u.length(f.combiner.image_distance_mm)));
  h += row("Beam-shaping lens: " + esc(s.lens.name),
           s.lens.enabled ? QString("f = %1, Ø %2, at %3, rotated %4")
                                .arg(u.length(s.lens.focal_length_mm), u.length(s.lens.diameter_mm),
                                     vec(s.lens.pose.position_mm, u), rot(s.lens.pose.rotation_deg, u))
                          : QString("not used"));
  h += row("Foveation", QString("blur from %1, blend %2 … %3")
                            .arg(u.angle(s.foveation.blur_start_deg), u.angle(s.foveation.blend_start_deg),
                                 u.angle(s.foveation.blend_end_deg)));
  QStringList stages;
  for (const StageBinding& b : s.stages)
    stages << QString("%1.%2 ← %3").arg(esc(b.element), esc(b.axis), esc(b.stage_model));
  h += row("Stages", stages.isEmpty() ? QString("none") : stages.join(", "));
  return h + "</table>";
}

ReportContent composeReport(MainWindow& window, const ReportData& d, const QList<PlotData>& extraPlots,
                            const DisplayUnits& u, const GazeViewCapture& gazeCapture) {
  ReportContent c;
  c.sceneName = QString::fromStdString(d.scene.name);
  c.scenePath = d.scenePath;
  c.title = d.options.title.isEmpty() ? QString("Design report: %1").arg(c.sceneName) : d.options.title;
  if (!d.eye.isEmpty() && d.options.title.isEmpty()) c.title += QString(" (%1 eye)").arg(d.eye);
  c.created = QDateTime::currentDateTime();
  c.sceneTableHtml = sceneSummaryTableHtml(d.scene, u);
  c.keyNumbersHtml = keyNumbersHtml(d, u);
  c.problems = d.problems;
  c.eye = d.eye;
  c.eyes = d.eyes;

  viz::SceneView* view = window.sceneView();
  // Printed figures: light background, no handles or selection box (restored at the end).
  const bool wasPrintLook = view->printLook();
  const bool wasEyeView = view->eyeViewMode();
  view->setPrintLook(true);
  vtkNew<vtkCamera> saved;
  saved->DeepCopy(view->renderer()->GetActiveCamera());
  const Scene shown = view->scene();
  const Eigen::Vector3d shownShift = view->hoeDisplayShift();
  // The gaze figures borrow the live overlay (its layers are the view's "rays", "eye_marks"
  // and "effmap"); without a live trace part a temporary one draws them.
  LiveTraceFeatures* live = window.liveTraceFeatures();
  std::unique_ptr<viz::TraceOverlay> own;
  viz::TraceOverlay* overlay = live ? live->overlay() : nullptr;
  if (!overlay) overlay = (own = std::make_unique<viz::TraceOverlay>(view)).get();
  const char* overlayLayers[] = {"rays", "eye_marks", "effmap"};
  bool layerWasVisible[3];
  for (int k = 0; k < 3; ++k) {
    viz::SceneLayer& l = view->layer(overlayLayers[k]);
    layerWasVisible[k] = l.isVisible();
    l.setVisible(true);
  }
  // A binocular live view's left-eye overlay is not the report's (its figures are of one eye's
  // trace): hidden, and the left HOE back at the mirror of the drawn one's; restored below.
  const char* leftLayers[] = {"left-rays", "left-eye_marks"};
  bool leftWasVisible[2];
  for (int k = 0; k < 2; ++k) {
    viz::SceneLayer& l = view->layer(leftLayers[k]);
    leftWasVisible[k] = l.isVisible();
    l.setVisible(false);
  }
  view->setLeftHoeDisplayShift(std::nullopt);
  overlay->clear();  // the standard views: the bench alone
  view->setScene(d.scene);

  if (d.eyes.is_object()) c.sections << bothEyesSection(d, u);

  ReportSection views{"3-D views", "The bench at its real size and pose, from the standard angles.", {}};
  const struct {
    viz::StandardView v;
    const char* id;
    const char* caption;
  } standard[] = {
      {viz::StandardView::Isometric, "view-iso",
       "Isometric view from the world side: projector, HOE, eye and micro-OLED."},
      {viz::StandardView::Top, "view-top",
       "Top view (from +y, the world at the top): the horizontal layout of the bench."},
      {viz::StandardView::Side, "view-side", "Side view from the projector's side (+x)."},
      {viz::StandardView::EyeView, "view-eye",
       "The eye's view along its gaze: what the HOE covers of the visual field."},
  };
  for (const auto& s : standard) {
    if (s.v == viz::StandardView::EyeView) {
      // From the pupil the plate alone is an orange slab filling the frame: draw what the eye
      // sees of it, the area whose rays enter the pupil coloured by their efficiency, from the
      // trace at the scene's gaze (else the first traced gaze, the eye turned to it).
      const GazeTrace* trace = d.traces.isEmpty() ? nullptr : &d.traces.front();
      for (const GazeTrace& t : d.traces)
        if (t.gaze_deg == d.scene.eye.gaze_deg) trace = &t;
      QString caption = s.caption;
      if (trace) {
        Scene turned = d.scene;
        turned.eye.gaze_deg = trace->gaze_deg;
        view->setScene(turned);
        const Frame plate = frameOf(d.scene.hoe.pose);
        view->setHoeDisplayShift(trace->hoe_shift_mm[0] * plate.x() + trace->hoe_shift_mm[1] * plate.y());
        view->showStandardView(s.v);
        overlay->show(turned, trace->rays, trace->grid, trace->hoe_shift_mm, viz::TraceOverlayOptions{});
        caption = QString(
                      "The eye's view along its gaze %1: the part of the HOE whose rays enter the pupil, "
                      "coloured by their mean diffraction efficiency (colour bar), on the plate seen from the "
                      "pupil.")
                      .arg(gazeText(trace->gaze_deg, u));
      } else {
        view->showStandardView(s.v);
      }
      ReportFigure f{s.id, caption, capture3d(view), {}};
      if (!f.image.isNull()) views.figures << f;
      overlay->clear();
      view->setScene(d.scene);
      view->setHoeDisplayShift(Eigen::Vector3d::Zero());
      continue;
    }
    view->showStandardView(s.v);
    ReportFigure f{s.id, s.caption, capture3d(view), {}};
    if (!f.image.isNull()) views.figures << f;
  }
  c.sections << views;

  ReportSection gazes{"The bench at the chosen gazes",
                      "Top views with the eye turned to each chosen gaze and the ray fans of that gaze's trace: "
                      "projector → HOE → pupil, coloured by diffraction efficiency, solid into the pupil, dashed "
                      "where they miss it, gray below 10 %; the pupil in green, the fovea in orange.",
                      {}};
  viz::TraceOverlayOptions fans;  // horizontal fan, every wavelength, no efficiency map
  fans.fan_rays = 61;             // dense enough on paper to tell one gaze's fans from another's
  for (int i = 0; i < d.options.gazes_deg.size(); ++i) {
    const auto gz = d.options.gazes_deg[i];
    const GazeTrace* trace = nullptr;
    for (const GazeTrace& t : d.traces)
      if (t.gaze_deg == gz) trace = &t;
    GazeFigureStats stats;
    stats.figureId = QString("gaze-%1").arg(i + 1);
    stats.gaze_deg = gz;
    QImage img;
    if (gazeCapture) {
      img = gazeCapture(gz);
    } else {
      Scene turned = d.scene;
      turned.eye.gaze_deg = gz;
      overlay->clear();
      view->setScene(turned);
      if (trace) {
        stats.hoe_shift_mm = trace->hoe_shift_mm;
        const Frame plate = frameOf(d.scene.hoe.pose);
        view->setHoeDisplayShift(trace->hoe_shift_mm[0] * plate.x() + trace->hoe_shift_mm[1] * plate.y());
      }
      view->showStandardView(viz::StandardView::Top);  // framed on the bench alone
      img = capture3d(view);
      if (trace && !img.isNull()) {
        const QImage plain = img;
        overlay->show(turned, trace->rays, trace->grid, trace->hoe_shift_mm, fans);
        stats.overlay = overlay->stats();
        overlay->colorBar()->VisibilityOff();  // count what the fans and marks change, not the bar
        stats.overlay_pixels = changedPixels(plain, capture3d(view));
        overlay->colorBar()->VisibilityOn();
        img = capture3d(view);
      }
    }
    QString caption = QString("Top view at gaze %1.").arg(gazeText(gz, u));
    if (trace) {
      const auto& f = trace->json.value("fov_deg", nlohmann::json::object());  // the exact FOV, as the table
      caption +=
          QString(" Retinal FOV there (exact) %1 × %2 %3, mean efficiency %4.")
              .arg(g(u.angleFromDeg(jsonNumber(f, {"horizontal"}))), g(u.angleFromDeg(jsonNumber(f, {"vertical"}))),
                   u.angleSymbol(), pct(trace->rays.mean_efficiency));
      if (trace->hoe_shift_mm != std::array<double, 2>{0, 0})
        caption += QString(" HOE following the gaze, shifted by (%1, %2) %3.")
                       .arg(g(u.lengthFromMm(trace->hoe_shift_mm[0])), g(u.lengthFromMm(trace->hoe_shift_mm[1])),
                            u.lengthSymbol());
      if (!gazeCapture)
        caption += QString(" %1 rays drawn, %2 into the pupil.")
                       .arg(stats.overlay.rays_drawn)
                       .arg(stats.overlay.rays_in_pupil);
    }
    if (!img.isNull()) {
      gazes.figures << ReportFigure{stats.figureId, caption, img.convertToFormat(QImage::Format_RGB32), {}};
      c.gazeFigures << stats;
    }
  }
  overlay->clear();
  own.reset();
  for (int k = 0; k < 3; ++k) view->layer(overlayLayers[k]).setVisible(layerWasVisible[k]);
  for (int k = 0; k < 2; ++k) view->layer(leftLayers[k]).setVisible(leftWasVisible[k]);
  view->setScene(shown);
  if (live)
    live->redraw();  // the live fans, effmap, retina and plate shift as they were
  else
    view->setHoeDisplayShift(shownShift);
  view->renderer()->GetActiveCamera()->DeepCopy(saved);
  view->renderer()->ResetCameraClippingRange();
  view->setEyeViewMode(wasEyeView);
  view->setPrintLook(wasPrintLook);
  view->requestRender();
  if (!gazes.figures.isEmpty()) c.sections << gazes;

  ReportSection retina{"Retina maps",
                       "What the eye receives from the peripheral display at each chosen gaze: the studio's retina "
                       "view, then the retina map with its axes.",
                       {}};
  for (int i = 0; i < d.traces.size(); ++i) {
    const GazeTrace& t = d.traces[i];
    auto r = std::make_shared<widgets::LiveTraceResult>();
    r->scene = d.scene;
    r->scene.eye.gaze_deg = t.gaze_deg;
    r->settings.rays = d.options.rays;
    r->settings.follow_gaze = d.options.follow_gaze;
    r->hoe_shift_mm = t.hoe_shift_mm;
    r->grid = t.grid;
    r->trace = t.rays;
    widgets::RetinaView retinaView;
    retinaView.setResult(r, {});
    const QImage seen = retinaView.render(QSize(760, 620));
    for (GazeFigureStats& s : c.gazeFigures)
      if (s.gaze_deg == t.gaze_deg) s.retina_cells = retinaView.cellsDrawn();
    if (!seen.isNull())
      retina.figures << ReportFigure{
          QString("retina-view-%1").arg(i + 1),
          QString("The retina view at gaze %1 (as the studio's Retina dock draws it).").arg(gazeText(t.gaze_deg, u)),
          seen,
          {}};
    const PlotData p = widgets::retinaMapPlot(t.rays, 0.1, u);
    if (p.isEmpty()) continue;
    retina.figures << ReportFigure{
        QString("retina-%1").arg(i + 1), p.caption, widgets::renderPlotImage(p, QSize(760, 620), 1.6), {}};
  }
  if (!retina.figures.isEmpty()) c.sections << retina;
  if (d.retinaImage && !d.retinaImage->image.isNull()) {
    const ReportRetinaImage& ri = *d.retinaImage;
    ReportSection image{"Retinal image",
                        "The test target on both displays as the retina receives it (issue 29): pixel beams through "
                        "the HOE and the accommodating schematic eye, the foveal inset through the defocused pupil, "
                        "efficiency shading and missing rays, in visual angle.",
                        {}};
    image.figures << ReportFigure{
        "retina-image",
        QString("The retinal image at gaze %1, accommodation %2 D (the foveal image's distance). Line of sight: "
                "peripheral spot %3 arcmin (MTF50 %4 cpd), foveal spot %5 arcmin (MTF50 %6 cpd); power on the "
                "retina %7 of %8 entering the pupil.")
                .arg(gazeText(ri.options.gaze_deg, u), QString::number(ri.options.accommodation_d, 'g', 3),
                     QString::number(ri.peripheral_spot_arcmin, 'f', 1),
                     QString::number(ri.peripheral_mtf50_cpd, 'g', 3), QString::number(ri.foveal_spot_arcmin, 'f', 2),
                     QString::number(ri.foveal_mtf50_cpd, 'g', 3), QString::number(ri.power_on_retina, 'g', 8),
                     QString::number(ri.power_in_pupil, 'g', 8)) +
            retinaImageOptionsText(ri),
        ri.image,
        {}};
    c.sections << image;
  }

  ReportSection plots{
      "Plots", "The design analyses (the same numbers as fovea-cli and the studio's analyses panel).", {}};
  QStringList done;
  auto addResult = [&](const char* id, const nlohmann::json& j) {
    if (!j.is_object()) return;
    for (const PlotData& p : widgets::plotsFromResult(id, j, u)) {
      addPlotFigure(plots.figures, p);
      done << p.id;
    }
  };
  addResult("sweep", d.sweep);
  addResult("selectivity", d.selectivity);
  addResult("resolution", d.resolution);
  addResult("kogelnik-vs-rcwa", d.kogelnikVsRcwa);
  const ReportSection tolerance = toleranceReportSection(d.tolerance, u);
  for (const widgets::PlotData& p : widgets::plotsFromResult("tolerance", d.tolerance, u)) done << p.id;
  for (const PlotData& p : extraPlots)
    if (!done.contains(p.id)) addPlotFigure(plots.figures, p);
  if (!plots.figures.isEmpty()) c.sections << plots;
  if (!tolerance.figures.isEmpty()) c.sections << tolerance;
  return c;
}

QString reportHtml(const ReportContent& c, bool embed) {
  auto imageSrc = [&](int n, const QImage& img) {
    if (!embed) return QString("figure-%1.png").arg(n);
    QByteArray bytes;
    QBuffer buffer(&bytes);
    buffer.open(QIODevice::WriteOnly);
    img.save(&buffer, "PNG");
    return QString("data:image/png;base64,") + QString::fromLatin1(bytes.toBase64());
  };
  QString h;
  if (embed) {
    h += "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'><title>" + esc(c.title) +
         "</title>\n<style>body{font-family:sans-serif;max-width:60em;margin:2em auto;padding:0 1em;color:#222}"
         "table{border-collapse:collapse;width:100%;margin:0.5em 0}td,th{border:1px solid #999;padding:4px 6px;"
         "vertical-align:top}th{background:#eee;text-align:left}figure{margin:1.5em 0;page-break-inside:avoid}"
         "figure img{max-width:100%;border:1px solid #ccc}figcaption{font-size:0.92em;color:#333;margin-top:0.3em}"
         "h2{border-bottom:1px solid #aaa;padding-bottom:0.2em;margin-top:2em}.meta{color:#555}</style></head><body>\n";
  } else {
    h += "<html><body style='font-family:sans-serif; font-size:10pt'>";
  }
  h += "<h1>" + esc(c.title) + "</h1>";
  h += "<p class='meta'>Scene <b>" + esc(c.sceneName) + "</b>" +
       (c.scenePath.isEmpty() ? QString(" (the embedded prototype bench)") : " — " + esc(c.scenePath)) +
       "<br>Generated " + c.created.toString("yyyy-MM-dd HH:mm") + " by Foveated AR Studio " + FOVEA_VERSION_STRING +
       ". Lengths and angles in the display units chosen in the preferences.</p>";
  h += "<h2>Scene summary</h2>" + c.sceneTableHtml;
  const QString pageBreak = embed ? QString() : QString(" style='page-break-before: always'");
  h += "<h2" + pageBreak + ">Key numbers</h2>" + c.keyNumbersHtml;
  if (!c.problems.isEmpty()) {
    h += "<p><b>Not computed:</b></p><ul>";
    for (const QString& p : c.problems) h += "<li>" + esc(p) + "</li>";
    h += "</ul>";
  }
  int n = 0;
  for (const ReportSection& s : c.sections) {
    h += "<h2" + pageBreak + ">" + esc(s.heading) + "</h2>";
    if (!s.introHtml.isEmpty()) h += "<p>" + s.introHtml + "</p>";
    int onPage = 0;  // PDF: at most two figures per page, never one split by a page break
    for (const ReportFigure& f : s.figures) {
      ++n;
      const bool full = !f.tableHtml.isEmpty();
      const bool newPage = !embed && (onPage >= 2 || (full && onPage > 0));
      onPage = newPage ? 1 : onPage + 1;
      if (full) onPage = 2;
      if (embed) {
        h += QString("<figure id='%1'><img src='%2' alt='Figure %3'><figcaption><b>Figure %3.</b> %4</figcaption>")
                 .arg(esc(f.id), imageSrc(n, f.image))
                 .arg(n)
                 .arg(esc(f.caption));
        if (!f.tableHtml.isEmpty()) h += f.tableHtml;
        h += "</figure>\n";
      } else {
        // QTextDocument: images are sized in points-like document units; 640 wide fills the text width.
        constexpr int kMaxW = 620, kMaxH = 370;  // two figures with captions per A4 page
        int w = kMaxW,
            hgt = static_cast<int>(std::lround(double(kMaxW) * f.image.height() / std::max(1, f.image.width())));
        if (hgt > kMaxH) w = static_cast<int>(w * double(kMaxH) / hgt), hgt = kMaxH;
        h += QString("<p align='center'%4><img src='%1' width='%2' height='%3'></p>")
                 .arg(imageSrc(n, f.image))
                 .arg(w)
                 .arg(hgt)
                 .arg(newPage ? QString(" style='page-break-before: always'") : QString());
        h += QString("<p><b>Figure %1.</b> %2</p>").arg(n).arg(esc(f.caption));
        if (!f.tableHtml.isEmpty()) h += f.tableHtml;
      }
    }
  }
  h += "</body></html>\n";
  return h;
}

bool writeReport(const ReportContent& c, const QString& path, QString* error, int* pages) {
  auto fail = [&](const QString& m) {
    if (error) *error = m;
    return false;
  };
  const QString ext = QFileInfo(path).suffix().toLower();
  QSaveFile out(path);
  if (ext == "html" || ext == "htm") {
    const QByteArray bytes = reportHtml(c, true).toUtf8();
    if (!out.open(QIODevice::WriteOnly) || out.write(bytes) != bytes.size() || !out.commit()) {
      out.cancelWriting();
      return fail(out.errorString());
    }
    return true;
  }
  if (ext != "pdf") return fail(QString("unknown report format \".%1\": use .pdf or .html").arg(ext));
  if (!out.open(QIODevice::WriteOnly)) return fail(out.errorString());
  int pageCount = 0;
  {
    QPdfWriter pdf(&out);
    pdf.setPageSize(QPageSize(QPageSize::A4));
    pdf.setPageMargins(QMarginsF(18, 15, 18, 15), QPageLayout::Millimeter);
    pdf.setResolution(300);
    pdf.setTitle(c.title);
    pdf.setCreator(QString("Foveated AR Studio ") + FOVEA_VERSION_STRING);

    QTextDocument doc;
    doc.setDocumentMargin(0);
    int n = 0;
    for (const ReportSection& s : c.sections)
      for (const ReportFigure& f : s.figures)
        doc.addResource(QTextDocument::ImageResource, QUrl(QString("figure-%1.png").arg(++n)), f.image);
    doc.setHtml(reportHtml(c, false));

    // Lay the document out in points-like units on a page of the paint rect's proportions,
    // then scale each page onto the device (as QTextDocument::print does).
    const QRectF paint = pdf.pageLayout().paintRectPixels(pdf.resolution());
    const double footer = paint.height() * 0.035;
    const double scale = pdf.resolution() / 96.0;  // document px -> device px
    const QSizeF pageInDoc(paint.width() / scale, (paint.height() - footer) / scale);
    doc.setPageSize(pageInDoc);
    pageCount = doc.pageCount();
    QPainter painter;
    if (!painter.begin(&pdf)) return fail(QStringLiteral("cannot start the PDF"));
    QFont footerFont("sans-serif");
    footerFont.setPointSizeF(8);
    for (int i = 0; i < pageCount; ++i) {
      if (i > 0) pdf.newPage();
      painter.save();
      painter.scale(scale, scale);
      painter.translate(0, -i * pageInDoc.height());
      QAbstractTextDocumentLayout::PaintContext ctx;
      ctx.clip = QRectF(0, i * pageInDoc.height(), pageInDoc.width(), pageInDoc.height());
      painter.setClipRect(ctx.clip);
      doc.documentLayout()->draw(&painter, ctx);
      painter.restore();
      painter.setFont(footerFont);
      painter.setPen(QColor(90, 90, 90));
      painter.drawText(QRectF(0, paint.height() - footer * 0.8, paint.width(), footer * 0.8),
                       Qt::AlignRight | Qt::AlignVCenter,
                       QString("%1 — page %2 of %3").arg(c.title).arg(i + 1).arg(pageCount));
    }
    painter.end();
  }
  if (!out.commit()) return fail(out.errorString());
  if (pages) *pages = pageCount;
  return true;
}

}  // namespace fovea::studio
