#pragma once
// The design report's Tolerance section, from a tolerance result (the document of
// `fovea-cli tolerance --json`, model/analysis/tolerance_run.h): the yield with its 95 %
// interval, the spec in a table (every tolerance with its distribution and the width it may
// take for the target yield, the gazes, compensator and pass criterion), the yield plot, one
// histogram per figure with its pass threshold, and the sensitivity ranking with its table.

#include <nlohmann/json.hpp>

#include "app/studio/report_document.h"
#include "widgets/preferences.h"

namespace fovea::studio {

// Empty (no figures) when `result` is not a tolerance result.
ReportSection toleranceReportSection(const nlohmann::json& result, const widgets::DisplayUnits& units);

// The spec summary table (HTML).
QString toleranceSpecTableHtml(const nlohmann::json& result);

}  // namespace fovea::studio
