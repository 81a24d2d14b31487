#pragma once
// From analysis results (the CLI-shaped JSON of analysis_catalog.h) to plots:
//   fov-vs-gaze, travel-vs-gaze            <- sweep
//   efficiency-vs-angle                    <- selectivity (every layer) or grating (Kogelnik, RCWA)
//   efficiency-vs-wavelength               <- selectivity
//   resolution-vs-eccentricity             <- resolution
//   resolution-vs-accommodation            <- resolution (with accommodation-d)
//   time-vs-error                          <- kogelnik-vs-rcwa
//   sensitivity                            <- sensitivity
//   lens-candidates                        <- optimize-lens
//   tolerance-yield, tolerance-ranking,    <- tolerance (yield with its 95 % interval, the
//   tolerance-<figure> (histograms)           sensitivity ranking, one histogram per figure)
//   fit-residuals                          <- fit
// Angles and lengths are shown in the preferred display units; the CSV table carries the
// same numbers as the plot, with the unit in each header.

#include <QList>
#include <QString>
#include <QStringList>

#include <nlohmann/json.hpp>

#include "model/physics/trace.h"
#include "widgets/plots/plot_data.h"
#include "widgets/preferences.h"

namespace fovea::widgets {

// Every plot id, in the order of the plots area's tabs.
QStringList plotIds();
QString plotTitle(const QString& plotId);
// The analyses that fill a plot ("sweep"), for the empty plot's hint.
QStringList plotSources(const QString& plotId);

// The plots fed by one result of `analysisId`; empty when it feeds none. `source` is the
// command line that produced it (stored in PlotData::source). Throws nothing: a result
// without the expected keys gives plots without points.
QList<PlotData> plotsFromResult(const QString& analysisId, const nlohmann::json& result, const DisplayUnits& units,
                                const QString& source = {});

// Retina map: the visual angle (yaw, pitch relative to the gaze) of every traced ray that
// enters the pupil, in efficiency classes (grey below the trace's threshold), with the FOV box
// of the rays that count. Needs a trace with keep_rays.
PlotData retinaMapPlot(const TraceResult& trace, double threshold, const DisplayUnits& units);

}  // namespace fovea::widgets
