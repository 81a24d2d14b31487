#pragma once
// The key numbers of an analysis result as a short HTML fragment (a table), in the preferred
// display units: shown by the analyses panel after a run and collected by the report.

#include <QString>

#include <nlohmann/json.hpp>

#include "widgets/preferences.h"

namespace fovea::widgets {

// What a tolerance yield's 95 % interval rests on ("12 independent samples: the A and B rows of
// the Saltelli design's 6 blocks ..."), from the yield object of the result (its
// "interval_basis", else its "independent_samples"); HTML-escaped.
QString toleranceIntervalBasis(const nlohmann::json& yield);

QString analysisSummaryHtml(const QString& analysisId, const nlohmann::json& result, const DisplayUnits& units);

}  // namespace fovea::widgets
