#include "widgets/analyses/analyses_panel.h"

#include <QApplication>
#include <QClipboard>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSpinBox>
#include <QTextBrowser>
#include <QToolButton>
#include <QVBoxLayout>

#include <cmath>

#include "widgets/analyses/analysis_summary.h"
#include "widgets/analyses/fit_form_extras.h"
#include "widgets/dialog_start.h"
#include "widgets/preferences.h"
#include "widgets/scene_document.h"

namespace fovea::widgets {

AnalysesPanel::AnalysesPanel(SceneDocument* document, QWidget* parent)
    : QWidget(parent), document_(document), runner_(new AnalysisRunner(this)) {
  setObjectName("AnalysesPanel");
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  combo_ = new QComboBox(this);
  combo_->setObjectName("analysis");
  for (const AnalysisSpec& s : analysisCatalog()) combo_->addItem(s.title, s.id);
  layout->addWidget(combo_);
  // The description and the form scroll; the buttons, progress and status below stay in
  // view (the dock adds no scroll area of its own around a panel that has one).
  auto* scroll = new QScrollArea(this);
  scroll->setObjectName("formScroll");
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  scroll->setFocusPolicy(Qt::NoFocus);  // Tab goes to the fields, not to the frameless area
  auto* scrolled = new QWidget(scroll);
  auto* column = new QVBoxLayout(scrolled);
  column->setContentsMargins(0, 0, 0, 0);
  description_ = new QLabel(scrolled);
  description_->setWordWrap(true);
  description_->setObjectName("description");
  column->addWidget(description_);
  formHost_ = new QWidget(scrolled);
  form_ = new QFormLayout(formHost_);
  form_->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
  form_->setRowWrapPolicy(QFormLayout::WrapLongRows);
  column->addWidget(formHost_);
  column->addStretch(1);
  scroll->setWidget(scrolled);
  layout->addWidget(scroll, 3);

  auto* buttons = new QHBoxLayout;
  runButton_ = new QPushButton(tr("Run"), this);
  runButton_->setObjectName("run");
  runButton_->setDefault(true);
  cancelButton_ = new QPushButton(tr("Cancel"), this);
  cancelButton_->setObjectName("cancel");
  cancelButton_->setEnabled(false);
  defaultsButton_ = new QPushButton(tr("Defaults"), this);
  defaultsButton_->setObjectName("defaults");
  cliButton_ = new QPushButton(tr("Copy CLI"), this);
  cliButton_->setObjectName("copyCli");
  cliButton_->setToolTip(tr("Copy the equivalent fovea-cli command"));
  buttons->addWidget(runButton_);
  buttons->addWidget(cancelButton_);
  buttons->addStretch(1);
  buttons->addWidget(defaultsButton_);
  buttons->addWidget(cliButton_);
  layout->addLayout(buttons);
  progress_ = new QProgressBar(this);
  progress_->setObjectName("progress");
  progress_->setRange(0, 1000);
  progress_->setValue(0);
  progress_->setTextVisible(true);
  progress_->setFormat("%p%");
  layout->addWidget(progress_);
  status_ = new QLabel(tr("Ready."), this);
  status_->setObjectName("status");
  status_->setWordWrap(true);
  layout->addWidget(status_);
  summary_ = new QTextBrowser(this);
  summary_->setObjectName("summary");
  summary_->setMinimumHeight(90);
  layout->addWidget(summary_, 2);

  connect(combo_, &QComboBox::currentIndexChanged, this, [this] { rebuildForm(); });
  connect(runButton_, &QPushButton::clicked, this, [this] { run(); });
  connect(cancelButton_, &QPushButton::clicked, this, &AnalysesPanel::cancel);
  connect(defaultsButton_, &QPushButton::clicked, this, &AnalysesPanel::resetParameters);
  connect(cliButton_, &QPushButton::clicked, this, [this] {
    const QString cmd = cliCommand();
    if (!cmd.isEmpty()) QApplication::clipboard()->setText(cmd);
    setStatus(currentAnalysis(), !cmd.isEmpty() ? tr("Copied: %1").arg(cmd) : cliUnavailableReason());
  });
  connect(runner_, &AnalysisRunner::progress, this, [this](const QString&, double f) {
    progress_->setValue(static_cast<int>(std::lround(1000.0 * f)));
    progress_->setFormat(progressFormat(f, runClock_.isValid() ? runClock_.elapsed() / 1000.0 : 0.0));
  });
  connect(runner_, &AnalysisRunner::finished, this, [this](const AnalysisResult& r) {
    results_[r.id] = r;
    progress_->setValue(1000);
    const AnalysisSpec* s = findAnalysis(r.id);
    setStatus(r.id, tr("%1 finished in %2 s.").arg(s ? s->title : r.id).arg(r.seconds, 0, 'f', 1));
    showSummary(r);
    if (fitExtras_ && r.id == "fit") fitExtras_->setResult(r);
    emit resultReady(r);
  });
  connect(runner_, &AnalysisRunner::failed, this, [this](const QString& id, const QString& message) {
    progress_->setValue(0);
    setStatus(id, tr("Failed: %1").arg(message));
  });
  connect(runner_, &AnalysisRunner::cancelled, this, [this](const QString& id) {
    progress_->setValue(0);
    setStatus(id, tr("Cancelled; no result."));
  });
  connect(runner_, &AnalysisRunner::idle, this, [this] { setBusy(false); });
  connect(&Preferences::instance(), &Preferences::changed, this, [this] {
    const QString id = currentAnalysis();
    if (results_.contains(id)) showSummary(results_[id]);
  });
  rebuildForm();
}

QString AnalysesPanel::currentAnalysis() const {
  return combo_->currentData().toString();
}

void AnalysesPanel::selectAnalysis(const QString& id) {
  const int i = combo_->findData(id);
  if (i >= 0) combo_->setCurrentIndex(i);
}

void AnalysesPanel::rememberForm() {
  const QString id = fields_.isEmpty() ? QString() : fields_.first()->property("analysis").toString();
  if (!id.isEmpty()) edited_[id] = parameters();
}

void AnalysesPanel::rebuildForm() {
  rememberForm();
  while (form_->rowCount() > 0) form_->removeRow(0);
  fields_.clear();
  fitExtras_ = nullptr;  // deleted with its row
  const AnalysisSpec* spec = findAnalysis(currentAnalysis());
  if (!spec) return;
  description_->setText(spec->description);
  const AnalysisParams values = edited_.value(spec->id, defaultParameters(*spec));
  for (const AnalysisParameter& p : spec->parameters) {
    QWidget* field = nullptr;
    QWidget* row = nullptr;  // the form row when it holds more than the field
    const QVariant v = values.value(p.key, p.defaultValue);
    switch (p.kind) {
      case AnalysisParameter::Kind::Number: {
        if (!p.defaultValue.isValid()) {  // may stay unset: empty means p.unsetMeaning
          auto* edit = new QLineEdit(formHost_);
          edit->setPlaceholderText(p.unsetMeaning);
          edit->setText(v.isValid() ? QString::number(v.toDouble(), 'g', 10) : QString());
          field = edit;
          break;
        }
        auto* box = new QDoubleSpinBox(formHost_);
        box->setDecimals(p.decimals);
        box->setRange(p.minimum, p.maximum);
        box->setValue(v.toDouble());
        box->setSingleStep(std::pow(10.0, -std::min(p.decimals, 2)) * (p.decimals > 0 ? 1 : 1));
        box->setKeyboardTracking(false);
        if (!p.unit.isEmpty()) box->setSuffix(" " + p.unit);
        field = box;
        break;
      }
      case AnalysisParameter::Kind::Integer: {
        auto* box = new QSpinBox(formHost_);
        box->setRange(static_cast<int>(p.minimum), static_cast<int>(std::min(p.maximum, 2e9)));
        box->setValue(v.toInt());
        field = box;
        break;
      }
      case AnalysisParameter::Kind::Choice: {
        auto* box = new QComboBox(formHost_);
        box->addItems(p.choices);
        box->setCurrentText(v.toString());
        field = box;
        break;
      }
      case AnalysisParameter::Kind::Text: {
        auto* box = new QComboBox(formHost_);
        box->setEditable(true);
        box->addItems(p.choices);
        box->setCurrentText(v.toString());
        field = box;
        break;
      }
      case AnalysisParameter::Kind::FilePath: {  // a path (empty: p.unsetMeaning) and "Browse…"
        auto* edit = new QLineEdit(formHost_);
        edit->setPlaceholderText(tr("default: %1").arg(p.unsetMeaning));
        edit->setText(v.isValid() ? v.toString() : QString());
        auto* browse = new QToolButton(formHost_);
        browse->setText(tr("…"));
        browse->setObjectName(p.key + "-browse");
        browse->setToolTip(tr("Choose the %1").arg(p.label.toLower()));
        connect(browse, &QToolButton::clicked, edit, [this, edit, label = p.label] {
          const QString f = QFileDialog::getOpenFileName(this, label, dialogStart(document_, edit->text()),
                                                         tr("JSON (*.json);;All files (*)"));
          if (!f.isEmpty()) edit->setText(f);
        });
        row = new QWidget(formHost_);
        auto* h = new QHBoxLayout(row);
        h->setContentsMargins(0, 0, 0, 0);
        h->addWidget(edit, 1);
        h->addWidget(browse);
        field = edit;
        break;
      }
    }
    field->setObjectName(p.key);
    field->setProperty("analysis", spec->id);
    field->setToolTip(
        QString("--%1: %2%3")
            .arg(p.key, p.help, p.unsetMeaning.isEmpty() ? QString() : tr(" (empty: %1)").arg(p.unsetMeaning)));
    form_->addRow(p.label, row ? row : field);
    fields_.insert(p.key, field);
  }
  if (spec->id == "fit") {
    fitExtras_ = new FitFormExtras(
        document_, [this](const QString& key) { return parameters().value(key); },
        [this](const QString& key, const QVariant& value) { setParameter(key, value); }, formHost_);
    fitExtras_->setResult(lastResult("fit"));
    connect(fitExtras_, &FitFormExtras::applied, this, [this](const QString& text) { setStatus("fit", text); });
    form_->addRow(QString(), fitExtras_);
  }
  cliButton_->setEnabled(spec->hasCliTwin);
  status_->setText(statusOf_.value(spec->id, tr("Ready.")));
  progress_->setValue(results_.contains(spec->id) ? 1000 : 0);
  if (results_.contains(spec->id))
    showSummary(results_[spec->id]);
  else
    summary_->clear();
}

void AnalysesPanel::setStatus(const QString& analysisId, const QString& text) {
  statusOf_[analysisId] = text;
  if (analysisId == currentAnalysis()) status_->setText(text);
}

AnalysisParams AnalysesPanel::parameters() const {
  AnalysisParams p;
  for (auto it = fields_.begin(); it != fields_.end(); ++it) {
    if (auto* d = qobject_cast<QDoubleSpinBox*>(it.value()))
      p[it.key()] = d->value();
    else if (auto* i = qobject_cast<QSpinBox*>(it.value()))
      p[it.key()] = i->value();
    else if (auto* c = qobject_cast<QComboBox*>(it.value()))  // an empty text field is unset
      p[it.key()] = c->isEditable() && c->currentText().trimmed().isEmpty() ? QVariant() : QVariant(c->currentText());
    else if (auto* e = qobject_cast<QLineEdit*>(it.value()))
      p[it.key()] = e->text().trimmed().isEmpty() ? QVariant() : QVariant(e->text().trimmed());
  }
  return p;
}

bool AnalysesPanel::setParameter(const QString& key, const QVariant& value) {
  QWidget* w = fields_.value(key);
  if (!w) return false;
  if (auto* d = qobject_cast<QDoubleSpinBox*>(w))
    d->setValue(value.toDouble());
  else if (auto* i = qobject_cast<QSpinBox*>(w))
    i->setValue(value.toInt());
  else if (auto* c = qobject_cast<QComboBox*>(w))
    c->setCurrentText(value.toString());
  else if (auto* e = qobject_cast<QLineEdit*>(w))
    e->setText(!value.isValid()                       ? QString()
               : value.typeId() == QMetaType::QString ? value.toString()
                                                      : QString::number(value.toDouble(), 'g', 10));
  return true;
}

void AnalysesPanel::resetParameters() {
  edited_.remove(currentAnalysis());
  fields_.clear();  // do not remember the form being replaced
  rebuildForm();
}

bool AnalysesPanel::run() {
  if (runner_->isRunning()) {
    setStatus(currentAnalysis(), tr("An analysis is already running."));
    return false;
  }
  const AnalysisSpec* spec = findAnalysis(currentAnalysis());
  if (!spec) return false;
  AnalysisParams p = parameters();
  const QStringList problems = validateParameters(*spec, p);
  if (!problems.isEmpty()) {
    setStatus(spec->id, tr("Not started: %1").arg(problems.join("; ")));
    return false;
  }
  progress_->setValue(0);
  runClock_.start();
  setStatus(spec->id, tr("Running %1 on %2…").arg(spec->title, document_->displayName()));
  setBusy(true);
  runner_->start(spec->id, document_->scene(), p);
  return true;
}

void AnalysesPanel::cancel() {
  if (!runner_->isRunning()) return;
  runner_->cancel();
  cancelButton_->setEnabled(false);
  setStatus(currentAnalysis(), tr("Cancelling: the running samples finish, no new one starts…"));
}

std::optional<AnalysisResult> AnalysesPanel::lastResult(const QString& id) const {
  if (!results_.contains(id)) return std::nullopt;
  return results_[id];
}

QString AnalysesPanel::statusText() const {
  return status_->text();
}

QString AnalysesPanel::progressText() const {
  return progress_->text();
}

QString AnalysesPanel::cliCommand() const {
  const AnalysisSpec* spec = findAnalysis(currentAnalysis());
  // fovea-cli reads the scene from its file: unsaved changes would not be in it.
  if (!spec || document_->isModified()) return {};
  return cliCommandLine(*spec, parameters(), document_->filePath());
}

QString AnalysesPanel::cliUnavailableReason() const {
  const AnalysisSpec* spec = findAnalysis(currentAnalysis());
  if (!spec || !spec->hasCliTwin) return tr("This analysis has no fovea-cli twin.");
  if (const QString why = widgets::cliUnavailableReason(*spec, parameters()); !why.isEmpty()) return why;
  if (!spec->definition->takes_scene) return {};
  if (document_->filePath().isEmpty())
    return tr("Save the scene first: fovea-cli reads the scene from a file, and this one has none yet.");
  if (document_->isModified()) return tr("Save the scene first: fovea-cli would not see the unsaved changes.");
  return {};
}

QString AnalysesPanel::progressFormat(double fraction, double elapsed_s) {
  // Time left from the rate so far, once there is a rate to speak of (2 s and 1 % done).
  if (!(fraction > 0.01 && fraction < 1.0) || elapsed_s < 2.0) return tr("%p% — running");
  const double left = elapsed_s * (1.0 - fraction) / fraction;
  const int s = static_cast<int>(std::lround(left));
  const QString t = s >= 60 ? tr("%1 min %2 s").arg(s / 60).arg(s % 60, 2, 10, QChar('0')) : tr("%1 s").arg(s);
  return tr("%p% — about %1 left").arg(t);
}

void AnalysesPanel::setBusy(bool busy) {
  runButton_->setEnabled(!busy);
  cancelButton_->setEnabled(busy);
  combo_->setEnabled(!busy);
  formHost_->setEnabled(!busy);
  progress_->setFormat(busy ? tr("%p% — running") : tr("%p%"));
}

void AnalysesPanel::showSummary(const AnalysisResult& r) {
  if (r.id != currentAnalysis() || !r.json) return;
  summary_->setHtml(QString("<p><b>%1</b> on %2</p>")
                        .arg(findAnalysis(r.id) ? findAnalysis(r.id)->title : r.id, r.sceneName.toHtmlEscaped()) +
                    analysisSummaryHtml(r.id, *r.json, Preferences::instance().units()));
}

}  // namespace fovea::widgets
