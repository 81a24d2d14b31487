#pragma once
// The extra controls of the "Fit to measurements" form (analysis "fit", docs/fitting.md): a
// file chooser for the targets, a list of the scene's number paths to add to the free
// parameters, and "Apply fitted values" — the last fit's values as one undoable edit. Thin:
// the fit itself is the registry's analysis run by the panel; the values are applied by
// model/analysis/fit_analysis.h sceneWithFittedValues.

#include <QWidget>

#include <functional>
#include <optional>

#include "widgets/analyses/analysis_runner.h"

class QComboBox;
class QPushButton;

namespace fovea::widgets {

class SceneDocument;

class FitFormExtras : public QWidget {
  Q_OBJECT
 public:
  // `parameter` reads a form field, `setParameter` writes one (the panel's).
  FitFormExtras(SceneDocument* document, std::function<QVariant(const QString&)> parameter,
                std::function<void(const QString&, const QVariant&)> setParameter, QWidget* parent = nullptr);

  // The result the Apply button applies (nothing: disabled).
  void setResult(const std::optional<AnalysisResult>& result);
  // Appends a free parameter spec to the form's list (what "Add" does with the chosen path).
  void addFreeParameter(const QString& spec);
  // Applies the fitted values of the result as one undo step; the problems, empty when applied.
  QStringList applyFittedValues();

 signals:
  void applied(const QString& message);

 private:
  void refillPaths();

  SceneDocument* document_;
  std::function<QVariant(const QString&)> parameter_;
  std::function<void(const QString&, const QVariant&)> setParameter_;
  QComboBox* paths_ = nullptr;
  QPushButton* apply_ = nullptr;
  std::optional<AnalysisResult> result_;
};

}  // namespace fovea::widgets
