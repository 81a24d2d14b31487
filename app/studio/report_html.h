#pragma once
// Text pieces shared by the design report's sections (report_document.cpp,
// report_tolerance.cpp): HTML escaping and the report's number formats.

#include <QString>
#include <string>

#include "widgets/number_text.h"

namespace fovea::studio::report_html {

inline QString esc(const QString& s) {
  return s.toHtmlEscaped();
}
inline QString esc(const std::string& s) {
  return QString::fromStdString(s).toHtmlEscaped();
}
// `significant` digits, the report's default 4 (widgets/number_text.h).
inline QString g(double v, int significant = 4) {
  return widgets::numberText(v, significant);
}
inline QString pct(double v) {
  return widgets::percentText(v);
}

}  // namespace fovea::studio::report_html
