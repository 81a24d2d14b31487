// The retina map of a live trace (no analysis JSON: it reads the trace's rays).
#include <QColor>

#include <algorithm>
#include <cmath>

#include "widgets/plots/plot_builders.h"
#include "widgets/plots/plot_helpers.h"

namespace fovea::widgets {

using namespace plots;  // NOLINT(google-build-using-namespace): the family helpers

PlotData retinaMapPlot(const TraceResult& trace, double threshold, const DisplayUnits& u) {
  PlotData p;
  p.id = "retina-map";
  p.title = QString("Retina map at gaze (%1, %2) %3")
                .arg(fmt(u.angleFromDeg(trace.gaze_deg[0])), fmt(u.angleFromDeg(trace.gaze_deg[1])), u.angleSymbol());
  p.x.title = withUnit("visual angle, yaw", u.angleSymbol());
  p.y.title = withUnit("visual angle, pitch", u.angleSymbol());
  struct Bin {
    double lo, hi;
    QColor color;
  };
  const Bin bins[] = {{0.0, threshold, QColor(175, 175, 175)}, {threshold, 0.3, QColor(68, 1, 84)},
                      {0.3, 0.5, QColor(59, 82, 139)},         {0.5, 0.7, QColor(33, 145, 140)},
                      {0.7, 0.85, QColor(94, 201, 98)},        {0.85, 1.0 + 1e-9, QColor(253, 200, 37)}};
  QVector<PlotSeries> classes;
  for (const Bin& b : bins) {
    PlotSeries s = series(b.lo == 0.0 ? QString("η < %1").arg(fmt(threshold, 2))
                                      : QString("η %1–%2").arg(fmt(b.lo, 2), fmt(std::min(1.0, b.hi), 2)),
                          Style::Scatter, b.color);
    s.markerSize = 4.0;
    classes << s;
  }
  p.columns = {withUnit("yaw", u.angleSymbol()),
               withUnit("pitch", u.angleSymbol()),
               "wavelength (nm)",
               "efficiency",
               "pixel x",
               "pixel y"};
  double ymin = INFINITY, ymax = -INFINITY, pmin = INFINITY, pmax = -INFINITY;
  for (const TracedRay& r : trace.ray_list) {
    if (!r.in_pupil) continue;
    const double y = u.angleFromDeg(r.field_deg[0]), pt = u.angleFromDeg(r.field_deg[1]);
    for (int b = 0; b < 6; ++b)
      if (r.efficiency >= bins[b].lo && r.efficiency < bins[b].hi) {
        addPoint(classes[b], y, pt);
        break;
      }
    if (r.efficiency >= threshold) {
      ymin = std::min(ymin, y), ymax = std::max(ymax, y);
      pmin = std::min(pmin, pt), pmax = std::max(pmax, pt);
    }
    p.rows.append(
        {cell(y), cell(pt), cell(r.wavelength_nm), cell(r.efficiency), QVariant(r.pixel[0]), QVariant(r.pixel[1])});
  }
  for (const PlotSeries& s : classes)
    if (!s.points.isEmpty()) p.series << s;
  if (ymin < ymax) {
    PlotSeries box = series("FOV box", Style::Dashed, QColor(20, 20, 20));
    box.points = {QPointF(ymin, pmin), QPointF(ymax, pmin), QPointF(ymax, pmax), QPointF(ymin, pmax),
                  QPointF(ymin, pmin)};
    p.series << box;
  }
  p.caption = QString(
                  "Retina map at gaze (%1, %2) %3: the visual angle of every projector ray entering the pupil "
                  "(all wavelengths), coloured by diffraction efficiency; the dashed box is the FOV of the rays "
                  "with η ≥ %4: %5 × %6 %3 (diagonal %7 %3), mean efficiency %8.")
                  .arg(fmt(u.angleFromDeg(trace.gaze_deg[0])), fmt(u.angleFromDeg(trace.gaze_deg[1])), u.angleSymbol(),
                       fmt(threshold, 2), fmt(u.angleFromDeg(trace.fov_deg.horizontal)),
                       fmt(u.angleFromDeg(trace.fov_deg.vertical)), fmt(u.angleFromDeg(trace.fov_deg.diagonal)),
                       fmt(trace.mean_efficiency, 3));
  return p;
}

}  // namespace fovea::widgets
