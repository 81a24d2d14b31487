#pragma once
// The design report: composed on the GUI thread from computed ReportData (report_data.h) and
// the studio's 3-D view, then written as PDF (QTextDocument laid out page by page on a
// QPdfWriter, A4, numbered pages) or as one self-contained HTML file (every image embedded as
// a base64 data URI). Sections: title page with the scene summary table; key numbers (FOV,
// eye box, HOE travel, efficiencies, resolution); for both eyes of a binocular scene a "Both eyes"
// section (each eye's FOV, efficiency and x_p, ReportData::eyes); 3-D views from the standard angles; the
// bench at each chosen gaze; retina maps; plots; tolerance (report_tolerance.h) when a tolerance
// result is there; each figure numbered and captioned.

#include <QDateTime>
#include <QImage>
#include <QList>
#include <QString>
#include <QStringList>

#include <array>
#include <functional>

#include "app/studio/report_data.h"
#include "viz/trace_overlay.h"
#include "widgets/plots/plot_data.h"
#include "widgets/preferences.h"

namespace fovea::studio {

class MainWindow;

struct ReportFigure {
  QString id;  // "view-iso", "gaze-1", "retina-1", "plot:fov-vs-gaze", ...
  QString caption;
  QImage image;
  QString tableHtml;  // optional table printed under the figure
};

struct ReportSection {
  QString heading;
  QString introHtml;
  QList<ReportFigure> figures;
};

// What a "bench at the chosen gaze" figure shows (for the manifest and tests).
struct GazeFigureStats {
  QString figureId;  // "gaze-N"
  std::array<double, 2> gaze_deg{0, 0};
  std::array<double, 2> hoe_shift_mm{0, 0};  // x_p the plate is drawn shifted by
  viz::TraceOverlayStats overlay;            // the ray fans drawn (viz::TraceOverlay)
  int overlay_pixels = 0;                    // pixels the fans and eye marks change against the same view without them
  int retina_cells = 0;                      // cells the retina view (widgets::RetinaView) drew for that gaze
};

struct ReportContent {
  QString title;
  QString sceneName, scenePath;
  QDateTime created;
  QString sceneTableHtml;
  QString keyNumbersHtml;
  QList<ReportSection> sections;
  QStringList problems;  // analyses that could not be computed
  QList<GazeFigureStats> gazeFigures;
  QString eye;          // ReportData::eye
  nlohmann::json eyes;  // ReportData::eyes
  int figureCount() const;
};

// Renders the 3-D view for a gaze (the bench with the eye turned to it, and whatever layers
// the view draws for that gaze). Default: the top view of the bench with the eye turned to
// the gaze and the report trace's ray fans drawn by viz::TraceOverlay (projector -> HOE ->
// pupil, efficiency-coloured, colour bar, pupil and fovea), the plate shifted by its x_p.
using GazeViewCapture = std::function<QImage(const std::array<double, 2>& gaze_deg)>;

// Composes the report. `extraPlots` (e.g. the plots area's other filled plots) are appended.
// The standard views show the bench without the live trace overlay. The window's view
// camera, scene, HOE display shift and live overlay are restored afterwards.
ReportContent composeReport(MainWindow& window, const ReportData& data, const QList<widgets::PlotData>& extraPlots,
                            const widgets::DisplayUnits& units, const GazeViewCapture& gazeCapture = {});

// Appends the figure of a plot (skipped when it has no points), its summary table under it.
void addPlotFigure(QList<ReportFigure>& out, const widgets::PlotData& plot);

// The report's HTML. `embedImages`: data URIs (a self-contained file); else "figure-N.png"
// resource names (used for the PDF's QTextDocument).
QString reportHtml(const ReportContent& content, bool embedImages);

// Writes by extension (.pdf or .html/.htm). `pages` gets the PDF page count. The file is
// replaced only by a complete one.
bool writeReport(const ReportContent& content, const QString& path, QString* error = nullptr, int* pages = nullptr);

// The scene summary table (title page): every element with its key parameters.
QString sceneSummaryTableHtml(const Scene& scene, const widgets::DisplayUnits& units);

}  // namespace fovea::studio
