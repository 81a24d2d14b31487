#include "widgets/bench/axis_table.h"

#include <QButtonGroup>
#include <QDoubleSpinBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QRadioButton>
#include <QVBoxLayout>

#include <cmath>

#include "devices/apt/stage_models.h"
#include "devices/stage/stage_binding.h"
#include "widgets/preferences.h"

namespace fovea::widgets {

namespace {
QString axisKey(const StageBinding& b) {
  return QString::fromStdString(b.element + "." + b.axis);
}
// Readouts keep the model's units with fixed decimals (the tests and the eye read them).
QString fixed(double v, const QString& unit) {
  return QString::number(v, 'f', unit == "deg" ? 2 : 3) + (unit == "deg" ? QStringLiteral("°") : " " + unit);
}
}  // namespace

// A Stage's refusal quotes the stage's own coordinates: say what they are in the row's frame.
QString AxisTable::stageFrameHint(const Row& r, const QString& error) const {
  const StageBinding b = r.worker->binding();
  if (!error.contains("limits") && !error.contains("travel")) return {};
  return tr(" (the controller's numbers are stage coordinates: %1 = stage %2 %3; in %1 coordinates the soft "
            "limits are %4 … %5)")
      .arg(QString::fromStdString(b.element), b.home_offset >= 0 ? "+" : "−",
           formatAxisValue(std::abs(b.home_offset), r.unit), formatAxisValue(b.soft_limits[0], r.unit),
           formatAxisValue(b.soft_limits[1], r.unit));
}

QString formatFocusImage(const FocusStageModel& model, double axis_mm) {
  const double d_mm = imageDistanceForFocusAxis(model, axis_mm);
  if (!std::isfinite(d_mm) || d_mm <= 0) return QStringLiteral("image at ∞");
  return QString("%1 cm · %2 D").arg(d_mm / 10, 0, 'f', 1).arg(1000.0 / d_mm, 0, 'f', 2);
}

QString formatAxisValue(double value, const QString& unit) {
  const DisplayUnits u = Preferences::instance().units();
  if (unit == "deg") return u.angleUnit == AngleUnit::Degree ? fixed(value, unit) : u.angle(value, 5);
  return u.lengthUnit == LengthUnit::Millimetre ? fixed(value, unit) : u.length(value, 5);
}

AxisTable::AxisTable(QWidget* parent) : QGroupBox(tr("Axes"), parent) {
  grid_ = new QGridLayout(this);
  grid_->setContentsMargins(4, 4, 4, 4);
  grid_->setHorizontalSpacing(4);
  grid_->setVerticalSpacing(2);
  select_group_ = new QButtonGroup(this);
  select_group_->setExclusive(true);

  jog_controls_ = new QWidget(parent);
  auto* v = new QVBoxLayout(jog_controls_);
  v->setContentsMargins(0, 0, 0, 0);
  auto* jog = new QHBoxLayout;
  jog->addWidget(new QLabel(tr("Step"), jog_controls_));
  step_ = new QDoubleSpinBox(jog_controls_);
  step_->setObjectName("jogStep");
  step_->setDecimals(3);
  step_->setRange(0.001, 10.0);
  step_->setValue(0.1);
  step_->setSuffix(tr(" mm|°"));
  step_->setToolTip(
      tr("Jog step (mm for translation stages, degrees for rotation stages); keys + and - double and halve it"));
  jog->addWidget(step_);
  jog->addWidget(new QLabel(tr("Speed"), jog_controls_));
  speed_ = new QDoubleSpinBox(jog_controls_);
  speed_->setObjectName("jogSpeed");
  speed_->setDecimals(2);
  speed_->setRange(0.01, 50.0);
  speed_->setValue(1.0);
  speed_->setSuffix(tr(" /s"));
  speed_->setToolTip(tr("Jog speed (mm/s or deg/s)"));
  jog->addWidget(speed_);
  jog->addStretch();
  v->addLayout(jog);
  auto* keys = new QLabel(tr("Keys: ←/→ jog the selected axis, ↑/↓ select, +/− step, Esc stops all"), jog_controls_);
  keys->setStyleSheet("color: palette(mid);");
  keys->setWordWrap(true);
  v->addWidget(keys);
}

void AxisTable::setBench(devices::LiveBench* live) {
  clearRows();
  live_ = live;
  if (!live_) return;
  int c = 0;
  for (const char* h : {"", "axis", "position", "state"}) {
    auto* l = new QLabel(tr(h), this);
    l->setStyleSheet("font-weight: bold;");
    grid_->addWidget(l, 0, c++);
  }
  int r = 1;
  for (devices::AxisWorker* w : live_->bench().axes()) {
    Row axis;
    axis.worker = w;
    axis.key = axisKey(w->binding());
    const auto stage = apt::findStage(w->binding().stage_model);
    axis.unit = QString::fromStdString(stage ? stage->unit() : "mm");
    const bool emulated = live_->bench().virtualController(w->binding().element, w->binding().axis) != nullptr;
    axis.select = new QRadioButton(this);
    axis.select->setObjectName("select_" + axis.key);
    select_group_->addButton(axis.select);
    axis.name = new QLabel(axis.key + (emulated ? tr(" (virtual)") : QString()), this);
    axis.name->setObjectName("name_" + axis.key);
    axis.name->setToolTip(
        QString::fromStdString(w->binding().controller + " " + w->binding().serial + ", " + w->binding().stage_model));
    axis.position = new QLabel("—", this);
    axis.position->setObjectName("position_" + axis.key);
    axis.position->setMinimumWidth(80);
    axis.position->setAlignment(Qt::AlignRight | Qt::AlignVCenter);
    axis.position->setStyleSheet("font-family: monospace;");
    axis.focus = focus_model_ && w->binding().element == "foveal_display" && w->binding().axis == "z";
    axis.state = new QLabel(this);
    axis.state->setObjectName("state_" + axis.key);
    axis.state->setMinimumWidth(60);
    // A note ("refused: 9.929 mm > 8.000 mm", "stopped at 1.423 mm") wraps in its column
    // rather than being cut to its first word when the dock is narrow.
    axis.state->setWordWrap(true);
    axis.reverse = new QPushButton("◀", this);
    axis.reverse->setObjectName("jogReverse_" + axis.key);
    axis.forward = new QPushButton("▶", this);
    axis.forward->setObjectName("jogForward_" + axis.key);
    axis.home = new QPushButton(tr("Home"), this);
    axis.home->setObjectName("home_" + axis.key);
    axis.target = new QDoubleSpinBox(this);
    axis.target->setObjectName("target_" + axis.key);
    axis.target->setDecimals(3);
    // Any number: the field never clips what was typed; goTo() refuses and explains.
    axis.target->setRange(-1e6, 1e6);
    axis.target->setValue(0.0);
    // Sized for the numbers a stage reaches (the ±1e6 range would make it as wide as
    // "-1000000.000" and push Go out of a 1366-pixel window's Bench dock); a longer number
    // still goes in, the field scrolls.
    axis.target->setMaximumWidth(axis.target->fontMetrics().horizontalAdvance(QStringLiteral("-8888.888")) + 36);
    const auto& b = w->binding();
    axis.target->setToolTip(
        tr("Element coordinate; soft limits %1 … %2")
            .arg(formatAxisValue(b.soft_limits[0], axis.unit), formatAxisValue(b.soft_limits[1], axis.unit)));
    axis.go = new QPushButton(tr("Go"), this);
    axis.go->setObjectName("go_" + axis.key);
    for (QPushButton* pb : {axis.reverse, axis.forward}) pb->setFixedWidth(28);
    // Home and Go as wide as their words (the style's 80-pixel minimum for text buttons made
    // the row wider than a 1366-pixel window's Bench dock).
    for (QPushButton* pb : {axis.home, axis.go})
      pb->setMaximumWidth(pb->fontMetrics().horizontalAdvance(pb->text()) + 24);
    // Clicking a row keeps the keyboard on the panel (arrow keys jog, Esc stops).
    for (QAbstractButton* ab :
         std::initializer_list<QAbstractButton*>{axis.select, axis.reverse, axis.forward, axis.home})
      ab->setFocusPolicy(Qt::NoFocus);
    connect(axis.select, &QRadioButton::clicked, this, [this] {
      if (parentWidget()) parentWidget()->setFocus();
    });
    c = 0;
    for (QWidget* wd : std::initializer_list<QWidget*>{axis.select, axis.name, axis.position, axis.state, axis.reverse,
                                                       axis.forward, axis.home, axis.target, axis.go})
      grid_->addWidget(wd, r, c++);
    const QString key = axis.key;
    connect(axis.reverse, &QPushButton::clicked, this, [this, key] { jog(key, -1); });
    connect(axis.forward, &QPushButton::clicked, this, [this, key] { jog(key, +1); });
    connect(axis.home, &QPushButton::clicked, this, [this, key] {
      if (Row* ar = row(key)) submit(*ar, tr("home"), [](devices::Stage& s) { s.home(); });
    });
    connect(axis.go, &QPushButton::clicked, this, [this, key] {
      if (Row* ar = row(key)) goTo(key, ar->target->value());
    });
    rows_.push_back(std::move(axis));
    ++r;
  }
  if (!rows_.empty()) rows_.front().select->setChecked(true);
}

void AxisTable::clearRows() {
  rows_.clear();
  for (QAbstractButton* b : select_group_->buttons()) select_group_->removeButton(b);
  while (QLayoutItem* item = grid_->takeAt(0)) {
    if (QWidget* w = item->widget()) w->deleteLater();
    delete item;
  }
  live_ = nullptr;
}

AxisTable::Row* AxisTable::row(const QString& key) {
  for (auto& r : rows_)
    if (r.key == key) return &r;
  return nullptr;
}

const AxisTable::Row* AxisTable::row(const QString& key) const {
  for (const auto& r : rows_)
    if (r.key == key) return &r;
  return nullptr;
}

void AxisTable::setRowNote(const QString& key, const QString& note, const QString& message, bool error) {
  if (Row* r = row(key)) {
    setNote(*r, note, message, error);
    refresh();
  }
}

void AxisTable::setNote(Row& r, const QString& note, const QString& message, bool error) {
  r.note = note;
  r.note_tip = message;
  r.note_error = error;
}

QString AxisTable::stateText(const QString& key) const {
  const Row* r = row(key);
  return r ? r->state->text() : QString();
}

void AxisTable::refresh() {
  for (auto& r : rows_) {
    const devices::AxisSnapshot s = r.worker->snapshot();
    // After Esc: once the axis stands, its state says where (the row's frame), and so does the report.
    if (r.stop_pending && s.state.known && !s.state.moving && !s.busy && *r.pending == 0) {
      r.stop_pending = false;
      const QString at = formatAxisValue(s.element_position, r.unit);
      r.note = tr("stopped at %1").arg(at);
      r.note_tip = tr("%1: stopped at %2 by the emergency stop (Esc)").arg(r.key, at);
      r.note_error = true;
      emit report(r.note_tip, true);
    }
    // An error no command of this table reported (a follow-gaze move): report it once.
    if (!s.last_error.empty() && s.last_error != r.seen_error) {
      r.seen_error = s.last_error;
      if (*r.pending == 0 && r.note.isEmpty()) {
        emit report(tr("%1: %2").arg(r.key, QString::fromStdString(s.last_error)) +
                        stageFrameHint(r, QString::fromStdString(s.last_error)),
                    true);
        r.note = tr("error");
        r.note_tip = QString::fromStdString(s.last_error);
        r.note_error = true;
      }
    }
    QString position = s.state.known ? fixed(s.element_position, r.unit) : QStringLiteral("—");
    if (r.focus && s.state.known) position += "\n" + formatFocusImage(*focus_model_, s.element_position);
    r.position->setText(position);
    QString st;
    if (!s.connected)
      st = tr("offline");
    else if (s.state.homing)
      st = tr("homing");
    else if (s.state.moving || s.busy)
      st = tr("moving");
    else if (!s.state.enabled)
      st = tr("disabled");
    else if (!s.state.homed)
      st = tr("not homed");
    else
      st = tr("ready");
    if (s.state.forward_limit || s.state.reverse_limit) st += tr(" · limit");
    if (!r.note.isEmpty()) {
      r.state->setText(r.note);
      r.state->setToolTip(r.note_tip);
      r.state->setStyleSheet(r.note_error ? "color: #c62828; font-weight: bold;" : "");
    } else {
      r.state->setText(st);
      r.state->setToolTip(QString::fromStdString(s.last_error));
      r.state->setStyleSheet("");
    }
    // The controller set-up read on connect (and what the scene had written).
    const QString device = QString::fromStdString(s.controller + " " + s.serial + ", " + s.stage_model);
    r.name->setToolTip(s.controller_setup.empty() ? device
                                                  : device + "\n" + QString::fromStdString(s.controller_setup));
  }
}

void AxisTable::submit(Row& row, const QString& what, std::function<void(devices::Stage&)> command) {
  row.note.clear();  // a new command: the last refusal or stop no longer describes the axis
  row.stop_pending = false;
  const QString key = row.key;
  const QString unit = row.unit;
  const StageBinding binding = row.worker->binding();
  auto pending = row.pending;
  auto unfinished = row.unfinished;
  auto stops = stops_;
  const int stops_before = *stops;
  ++*pending;
  ++*unfinished;
  row.worker->submit([this, key, unit, binding, what, command = std::move(command), pending, unfinished, stops,
                      stops_before](devices::Stage& s) {
    QString error;
    bool stopped_by_user = false;
    double stopped_at = 0;
    try {
      command(s);
    } catch (const std::exception& e) {
      error = QString::fromStdString(e.what());
      stopped_by_user = *stops != stops_before;
      stopped_at = devices::stageToElement(binding, s.state().position);
    }
    --*unfinished;
    // Queued to the GUI thread; dropped if the table is gone (the panel joins the workers first).
    QMetaObject::invokeMethod(
        this,
        [this, key, unit, what, error, stopped_by_user, stopped_at, pending] {
          // Counted down here, after the result is reported, so refresh() never reports it first.
          --*pending;
          Row* r = this->row(key);
          if (error.isEmpty()) {
            emit report(tr("%1: %2 done").arg(key, what), false);
          } else if (stopped_by_user) {  // in the row's frame, not the stage's raw coordinate
            const QString text = tr("%1: %2 stopped by you at %3").arg(key, what, formatAxisValue(stopped_at, unit));
            if (r) {
              r->stop_pending = false;
              r->note = tr("stopped at %1").arg(formatAxisValue(stopped_at, unit));
              r->note_tip = text;
              r->note_error = true;
            }
            emit report(text, true);
          } else {
            const QString text =
                tr("%1: %2 refused or failed — %3").arg(key, what, error) + (r ? stageFrameHint(*r, error) : QString());
            if (r) {
              r->seen_error = error.toStdString();
              r->note = tr("refused");
              r->note_tip = text;
              r->note_error = true;
            }
            emit report(text, true);
          }
          refresh();
        },
        Qt::QueuedConnection);
  });
}

void AxisTable::noteEmergencyStop() {
  ++*stops_;
  for (auto& r : rows_) {
    const devices::AxisSnapshot s = r.worker->snapshot();
    if (s.state.moving || s.state.homing || s.busy || *r.pending > 0) r.stop_pending = true;
  }
}

void AxisTable::refuse(Row& r, const QString& what, double value) {
  const StageBinding b = r.worker->binding();
  const QString lo = formatAxisValue(b.soft_limits[0], r.unit), hi = formatAxisValue(b.soft_limits[1], r.unit);
  const QString text = tr("%1: %2 %3 refused — outside the soft limits %4 … %5 (%6 coordinates); nothing was sent")
                           .arg(r.key, what, formatAxisValue(value, r.unit), lo, hi, QString::fromStdString(b.element));
  const bool below = value < b.soft_limits[0];
  setNote(r, tr("refused: %1 %2 %3").arg(formatAxisValue(value, r.unit), below ? "<" : ">", below ? lo : hi), text,
          true);
  emit report(text, true);
  refresh();
}

void AxisTable::jog(const QString& key, int direction) {
  Row* r = row(key);
  if (!r) return;
  // Key auto-repeat: at most one jog queued behind the running one. Counted on the worker, not by
  // `pending`: under load a finished jog's report can still wait in the GUI queue, and counting it
  // dropped a deliberate second click (tst_devices_panel, 1 of 3 loaded full runs, 2026-12-05).
  if (*r->unfinished > 1) return;
  const double step = step_->value(), speed = speed_->value();
  // A jog that would leave the soft limits is refused here, in the row's frame (the Stage would
  // refuse it in its own coordinates).
  const devices::AxisSnapshot snap = r->worker->snapshot();
  if (snap.state.known && *r->pending == 0) {
    const double to = snap.element_position + (direction > 0 ? step : -step);
    const StageBinding b = r->worker->binding();
    if (to < b.soft_limits[0] - 1e-9 || to > b.soft_limits[1] + 1e-9) {
      refuse(*r, tr("jog to"), to);
      return;
    }
  }
  submit(*r, direction > 0 ? tr("jog +%1").arg(step) : tr("jog −%1").arg(step),
         [step, speed, direction](devices::Stage& s) {
           devices::JogSettings j = s.jogSettings();
           if (j.continuous || std::abs(j.step - step) > 1e-9 || std::abs(j.max_velocity - speed) > 1e-9) {
             j.continuous = false;
             j.step = step;
             j.max_velocity = speed;
             if (!(j.acceleration > 0)) j.acceleration = 4.0 * speed;
             s.setJogSettings(j);
           }
           s.jog(direction > 0 ? apt::JogDirection::Forward : apt::JogDirection::Reverse);
         });
}

void AxisTable::goTo(const QString& key, double value) {
  Row* r = row(key);
  if (!r) return;
  const StageBinding b = r->worker->binding();
  const bool inside = std::isfinite(value) && value >= b.soft_limits[0] && value <= b.soft_limits[1];
  r->target->setStyleSheet(inside ? QString() : QStringLiteral("QDoubleSpinBox { background: #ffcdd2; }"));
  const QString lo = formatAxisValue(b.soft_limits[0], r->unit), hi = formatAxisValue(b.soft_limits[1], r->unit);
  if (!inside) {  // refused here: nothing is sent (the Stage would refuse it as well)
    r->target->setToolTip(tr("Refused: outside the soft limits %1 … %2").arg(lo, hi));
    refuse(*r, tr("go to"), value);
    return;
  }
  r->target->setToolTip(tr("Element coordinate; soft limits %1 … %2").arg(lo, hi));
  const double target = devices::elementToStage(b, value);
  submit(*r, tr("go to %1").arg(formatAxisValue(value, r->unit)),
         [target](devices::Stage& s) { s.moveAbsolute(target); });
}

void AxisTable::homeAll() {
  for (auto& r : rows_) submit(r, tr("home"), [](devices::Stage& s) { s.home(); });
}

double AxisTable::stepSize() const {
  return step_->value();
}
void AxisTable::setStepSize(double step) {
  step_->setValue(step);
}
void AxisTable::setSpeed(double speed) {
  speed_->setValue(speed);
}
void AxisTable::scaleStep(double factor) {
  step_->setValue(step_->value() * factor);
}

void AxisTable::setSelectedAxis(const QString& key) {
  if (Row* r = row(key)) r->select->setChecked(true);
}

QString AxisTable::selectedAxis() const {
  for (const auto& r : rows_)
    if (r.select->isChecked()) return r.key;
  return {};
}

void AxisTable::selectNext(int delta) {
  const QString sel = selectedAxis();
  const int n = static_cast<int>(rows_.size());
  for (int i = 0; i < n; ++i)
    if (rows_[static_cast<std::size_t>(i)].key == sel) {
      rows_[static_cast<std::size_t>(((i + delta) % n + n) % n)].select->setChecked(true);
      return;
    }
}

std::optional<double> AxisTable::axisPosition(const QString& key) const {
  const Row* r = row(key);
  if (!r) return std::nullopt;
  const devices::AxisSnapshot s = r->worker->snapshot();
  if (!s.state.known) return std::nullopt;
  return s.element_position;
}

}  // namespace fovea::widgets
