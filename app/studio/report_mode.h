#pragma once
// `fovea-studio [SCENE] --report FILE.pdf|FILE.html [--gaze-deg A[,B]]... [--rays N]
// [--report-tolerance N [--report-tolerance-spec FILE]] [--report-eye left|right|both]
// [--report-retina SPECKLE,GRAIN,CALIBRATION[,SEED]]`: the
// headless report (what `fovea-cli report` drives). The window is shown (an X display, e.g.
// Xvfb, gives VTK its OpenGL context), the analyses are computed, the report is written and
// a JSON manifest {"out","format","pages","figures","problems","gaze_figures","sections"} is
// printed to stdout. --report-tolerance N adds the Tolerance section (N trials of the spec, or of
// the shipped default spec).
// --report-retina sets the retinal image's options as the Foveated preview's Retina image
// controls do (the report takes them from there): speckle patterns per laser 0..16, grain
// "pixel" or "pupil", calibration "one" or "per-laser", speckle seed 1..999 (default 1); the
// manifest echoes them under "retina_image" {"speckle_patterns", "speckle_grain", "calibration",
// "speckle_seed"}.
// Exit codes: 0 written, 1 the report could not be written, 2 bad arguments.

#include <QString>
#include <QStringList>

namespace fovea::studio {

class MainWindow;

// `eye` (--report-eye): "left", "right" or "both" of a binocular scene, empty: both; the
// manifest then has "eye" (one eye) or "eyes" (each eye's key numbers, report_data.h).
int runReportMode(MainWindow& window, const QString& out, const QStringList& gazes, int rays, int toleranceTrials = 0,
                  const QString& toleranceSpec = {}, const QString& eye = {}, const QString& retina = {});

}  // namespace fovea::studio
