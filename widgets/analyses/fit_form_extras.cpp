#include "widgets/analyses/fit_form_extras.h"

#include <QComboBox>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QPushButton>
#include <QVBoxLayout>

#include "model/analysis/fit_analysis.h"
#include "model/scene/scene_fields.h"
#include "model/scene/scene_parameters.h"
#include "widgets/dialog_start.h"
#include "widgets/scene_document.h"

namespace fovea::widgets {

FitFormExtras::FitFormExtras(SceneDocument* document, std::function<QVariant(const QString&)> parameter,
                             std::function<void(const QString&, const QVariant&)> setParameter, QWidget* parent)
    : QWidget(parent), document_(document), parameter_(std::move(parameter)), setParameter_(std::move(setParameter)) {
  setObjectName("fitExtras");
  auto* rows = new QVBoxLayout(this);
  rows->setContentsMargins(0, 0, 0, 0);
  auto* browse = new QPushButton(tr("Targets file…"), this);
  browse->setObjectName("browseTargets");
  browse->setToolTip(tr("Choose a targets file (fovea-fit-targets JSON, docs/fitting.md)"));
  paths_ = new QComboBox(this);
  paths_->setObjectName("scenePaths");
  paths_->setToolTip(tr("Numbers of the scene file that can be fitted"));
  paths_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  paths_->setMinimumContentsLength(8);  // the paths are long: do not widen the dock
  auto* add = new QPushButton(tr("Add"), this);
  add->setObjectName("addFree");
  add->setToolTip(tr("Add the chosen path to the free parameters (default bounds)"));
  apply_ = new QPushButton(tr("Apply fitted values"), this);
  apply_->setObjectName("applyFit");
  apply_->setToolTip(tr("Set the last fit's values in the scene, as one undoable edit"));
  apply_->setEnabled(false);
  auto* pick = new QHBoxLayout;
  pick->addWidget(paths_, 1);
  pick->addWidget(add);
  rows->addLayout(pick);
  rows->addWidget(browse);
  rows->addWidget(apply_);
  connect(browse, &QPushButton::clicked, this, [this] {
    const QString f =
        QFileDialog::getOpenFileName(this, tr("Targets file"), dialogStart(document_, parameter_("targets").toString()),
                                     tr("Targets (*.json);;All files (*)"));
    if (!f.isEmpty()) setParameter_("targets", f);
  });
  connect(add, &QPushButton::clicked, this, [this] { addFreeParameter(paths_->currentText()); });
  connect(apply_, &QPushButton::clicked, this, [this] { applyFittedValues(); });
  connect(document_, &SceneDocument::sceneChanged, this, &FitFormExtras::refillPaths);
  refillPaths();
}

void FitFormExtras::refillPaths() {
  const QString current = paths_->currentText();
  paths_->clear();
  for (const auto& p : parameterPaths(document_->scene())) {
    const FieldInfo* info = fieldInfoAt(document_->scene(), p);
    if (!info || info->type == FieldType::Integer || info->type == FieldType::Integers) continue;  // not fitted
    paths_->addItem(QString::fromStdString(p));
  }
  if (!current.isEmpty()) paths_->setCurrentText(current);
}

void FitFormExtras::addFreeParameter(const QString& spec) {
  if (spec.trimmed().isEmpty()) return;
  QString list = parameter_("free").toString().trimmed();
  if ((" " + list + " ").contains(" " + spec + " ")) return;
  setParameter_("free", list.isEmpty() ? spec : list + " " + spec);
}

void FitFormExtras::setResult(const std::optional<AnalysisResult>& result) {
  result_ = result && result->json ? result : std::nullopt;
  apply_->setEnabled(result_.has_value());
}

QStringList FitFormExtras::applyFittedValues() {
  if (!result_) return {tr("No fit to apply yet.")};
  const nlohmann::json doc = *result_->json;
  int n = 0;
  for (const auto& p : doc.value("parameters", nlohmann::json::array())) n += p.value("determined", true) ? 1 : 0;
  QStringList problems;
  try {
    const Scene fitted = analysis::sceneWithFittedValues(document_->scene(), doc);
    problems = document_->applyEdit(tr("Apply fitted values (%1 parameters)").arg(doc["parameters"].size()),
                                    [&fitted](Scene& s) { s = fitted; });
  } catch (const std::exception& e) {
    problems = {QString::fromStdString(e.what())};
  }
  emit applied(
      problems.isEmpty()
          ? tr("Applied %1 fitted values (%2 determined) as one undoable edit.").arg(doc["parameters"].size()).arg(n)
          : tr("Not applied: %1").arg(problems.join("; ")));
  return problems;
}

}  // namespace fovea::widgets
