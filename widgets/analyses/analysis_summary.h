#pragma once
// The key numbers of an analysis result as a short HTML fragment (a table), in the preferred
// display units: shown by the analyses panel after a run and collected by the report.

#include <QString>

#include <nlohmann/json.hpp>

#include "widgets/preferences.h"

namespace fovea::widgets {

QString analysisSummaryHtml(const QString& analysisId, const nlohmann::json& result, const DisplayUnits& units);

}  // namespace fovea::widgets
