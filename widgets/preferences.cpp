#include "widgets/preferences.h"

#include <QApplication>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QPalette>
#include <QSettings>
#include <QSpinBox>
#include <QStyle>
#include <QStyleFactory>

#include "model/units.h"

namespace fovea::widgets {

namespace {

template <class E>
E fromKey(const QString& key, std::initializer_list<E> all, QString (*name)(E), E fallback) {
  for (E e : all)
    if (name(e) == key) return e;
  return fallback;
}

QString defaultStyleName() {
  static const QString name = QApplication::style() ? QApplication::style()->name() : QString();
  return name;
}

}  // namespace

double DisplayUnits::lengthFromMm(double mm) const {
  switch (lengthUnit) {
    case LengthUnit::Micrometre:
      return mm * 1000.0;
    case LengthUnit::Inch:
      return mm / 25.4;
    case LengthUnit::Millimetre:
      break;
  }
  return mm;
}

double DisplayUnits::angleFromDeg(double deg) const {
  return angleUnit == AngleUnit::Radian ? fovea::degToRad(deg) : deg;
}

double DisplayUnits::lengthToMm(double v) const {
  switch (lengthUnit) {
    case LengthUnit::Micrometre:
      return v / 1000.0;
    case LengthUnit::Inch:
      return v * 25.4;
    case LengthUnit::Millimetre:
      break;
  }
  return v;
}

double DisplayUnits::angleToDeg(double v) const {
  return angleUnit == AngleUnit::Radian ? fovea::radToDeg(v) : v;
}

QString DisplayUnits::lengthSymbol() const {
  switch (lengthUnit) {
    case LengthUnit::Micrometre:
      return QStringLiteral("µm");
    case LengthUnit::Inch:
      return QStringLiteral("in");
    case LengthUnit::Millimetre:
      break;
  }
  return QStringLiteral("mm");
}

QString DisplayUnits::angleSymbol() const {
  return angleUnit == AngleUnit::Radian ? QStringLiteral("rad") : QStringLiteral("deg");
}

QString DisplayUnits::length(double mm, int significant) const {
  return QString::number(lengthFromMm(mm), 'g', significant) + ' ' + lengthSymbol();
}

QString DisplayUnits::angle(double deg, int significant) const {
  return QString::number(angleFromDeg(deg), 'g', significant) + ' ' + angleSymbol();
}

Preferences& Preferences::instance() {
  static Preferences* p = new Preferences;  // lives as long as the process
  return *p;
}

QString Preferences::lengthUnitKey(LengthUnit u) {
  switch (u) {
    case LengthUnit::Micrometre:
      return "um";
    case LengthUnit::Inch:
      return "in";
    case LengthUnit::Millimetre:
      break;
  }
  return "mm";
}

QString Preferences::angleUnitKey(AngleUnit u) {
  return u == AngleUnit::Radian ? "rad" : "deg";
}

QString Preferences::themeKey(Theme t) {
  switch (t) {
    case Theme::Light:
      return "light";
    case Theme::Dark:
      return "dark";
    case Theme::System:
      break;
  }
  return "system";
}

void Preferences::load() {
  QSettings s;
  PreferenceValues v;
  v.length = fromKey(s.value("preferences/lengthUnit").toString(),
                     {LengthUnit::Millimetre, LengthUnit::Micrometre, LengthUnit::Inch}, &lengthUnitKey,
                     LengthUnit::Millimetre);
  v.angle = fromKey(s.value("preferences/angleUnit").toString(), {AngleUnit::Degree, AngleUnit::Radian}, &angleUnitKey,
                    AngleUnit::Degree);
  v.theme = fromKey(s.value("preferences/theme").toString(), {Theme::System, Theme::Light, Theme::Dark}, &themeKey,
                    Theme::System);
  bool ok = false;
  const int rays = s.value("preferences/defaultRays").toInt(&ok);
  if (ok && rays >= 50 && rays <= 1000000) v.defaultRays = rays;
  const int autosave = s.value("preferences/autosaveSeconds").toInt(&ok);
  if (ok && autosave >= 1 && autosave <= 600) v.autosaveSeconds = autosave;
  const int drag = s.value("preferences/dragResolutionPercent").toInt(&ok);
  if (ok && drag >= 25 && drag <= 100) v.dragResolutionPercent = drag;
  persistent_ = true;
  setValues(v);
}

void Preferences::setValues(const PreferenceValues& v) {
  const bool themeChanged = v.theme != values_.theme;
  values_ = v;
  if (persistent_) {
    QSettings s;
    s.setValue("preferences/lengthUnit", lengthUnitKey(v.length));
    s.setValue("preferences/angleUnit", angleUnitKey(v.angle));
    s.setValue("preferences/defaultRays", v.defaultRays);
    s.setValue("preferences/theme", themeKey(v.theme));
    s.setValue("preferences/autosaveSeconds", v.autosaveSeconds);
    s.setValue("preferences/dragResolutionPercent", v.dragResolutionPercent);
  }
  if (themeChanged || v.theme != Theme::System) applyTheme(v.theme);
  emit changed();
}

void Preferences::applyTheme(Theme theme) {
  if (!qApp) return;
  const QString base = defaultStyleName();
  if (theme == Theme::System) {
    if (!base.isEmpty()) QApplication::setStyle(QStyleFactory::create(base));
    QApplication::setPalette(QApplication::style()->standardPalette());
    return;
  }
  QApplication::setStyle(QStyleFactory::create("Fusion"));
  if (theme == Theme::Light) {
    QApplication::setPalette(QApplication::style()->standardPalette());
    return;
  }
  QPalette p;
  const QColor window(45, 47, 51), base_(30, 31, 34), text(225, 227, 230), accent(64, 140, 220);
  p.setColor(QPalette::Window, window);
  p.setColor(QPalette::WindowText, text);
  p.setColor(QPalette::Base, base_);
  p.setColor(QPalette::AlternateBase, window);
  p.setColor(QPalette::ToolTipBase, window);
  p.setColor(QPalette::ToolTipText, text);
  p.setColor(QPalette::Text, text);
  p.setColor(QPalette::Button, window);
  p.setColor(QPalette::ButtonText, text);
  p.setColor(QPalette::BrightText, Qt::red);
  p.setColor(QPalette::Link, accent);
  p.setColor(QPalette::Highlight, accent);
  p.setColor(QPalette::HighlightedText, Qt::white);
  p.setColor(QPalette::PlaceholderText, QColor(140, 142, 146));
  p.setColor(QPalette::Disabled, QPalette::Text, QColor(120, 122, 126));
  p.setColor(QPalette::Disabled, QPalette::ButtonText, QColor(120, 122, 126));
  p.setColor(QPalette::Disabled, QPalette::WindowText, QColor(120, 122, 126));
  QApplication::setPalette(p);
}

PreferencesDialog::PreferencesDialog(QWidget* parent) : QDialog(parent) {
  setWindowTitle(tr("Preferences"));
  setObjectName("PreferencesDialog");
  const PreferenceValues& v = Preferences::instance().values();
  auto* form = new QFormLayout;
  length_ = new QComboBox(this);
  length_->setObjectName("lengthUnit");
  length_->addItem(tr("millimetres (mm)"), "mm");
  length_->addItem(tr("micrometres (µm)"), "um");
  length_->addItem(tr("inches (in)"), "in");
  length_->setCurrentIndex(length_->findData(Preferences::lengthUnitKey(v.length)));
  angle_ = new QComboBox(this);
  angle_->setObjectName("angleUnit");
  angle_->addItem(tr("degrees"), "deg");
  angle_->addItem(tr("radians"), "rad");
  angle_->setCurrentIndex(angle_->findData(Preferences::angleUnitKey(v.angle)));
  rays_ = new QSpinBox(this);
  rays_->setObjectName("defaultRays");
  rays_->setRange(50, 1000000);
  rays_->setSingleStep(500);
  rays_->setValue(v.defaultRays);
  rays_->setSuffix(tr(" rays / wavelength"));
  theme_ = new QComboBox(this);
  theme_->setObjectName("theme");
  theme_->addItem(tr("System"), "system");
  theme_->addItem(tr("Light"), "light");
  theme_->addItem(tr("Dark"), "dark");
  theme_->setCurrentIndex(theme_->findData(Preferences::themeKey(v.theme)));
  autosave_ = new QSpinBox(this);
  autosave_->setObjectName("autosaveSeconds");
  autosave_->setRange(1, 600);
  autosave_->setValue(v.autosaveSeconds);
  autosave_->setSuffix(tr(" s"));
  form->addRow(tr("Display lengths in"), length_);
  form->addRow(tr("Display angles in"), angle_);
  form->addRow(tr("Default ray count"), rays_);
  form->addRow(tr("Theme"), theme_);
  dragResolution_ = new QSpinBox(this);
  dragResolution_->setObjectName("dragResolutionPercent");
  dragResolution_->setRange(25, 100);
  dragResolution_->setSingleStep(25);
  dragResolution_->setValue(v.dragResolutionPercent);
  dragResolution_->setSuffix(tr(" % of full"));
  dragResolution_->setToolTip(
      tr("The 3-D view draws at this resolution while a slider or handle is dragged, and at full "
         "resolution when the hand rests. Lower follows the hand faster on a software renderer."));
  form->addRow(tr("Autosave unsaved changes every"), autosave_);
  form->addRow(tr("3-D view resolution while dragging"), dragResolution_);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  form->addRow(buttons);
  setLayout(form);
}

PreferenceValues PreferencesDialog::chosen() const {
  PreferenceValues v;
  const QString l = length_->currentData().toString();
  v.length = l == "um" ? LengthUnit::Micrometre : l == "in" ? LengthUnit::Inch : LengthUnit::Millimetre;
  v.angle = angle_->currentData().toString() == "rad" ? AngleUnit::Radian : AngleUnit::Degree;
  v.defaultRays = rays_->value();
  const QString t = theme_->currentData().toString();
  v.theme = t == "dark" ? Theme::Dark : t == "light" ? Theme::Light : Theme::System;
  v.autosaveSeconds = autosave_->value();
  v.dragResolutionPercent = dragResolution_->value();
  return v;
}

void PreferencesDialog::accept() {
  Preferences::instance().setValues(chosen());
  QDialog::accept();
}

}  // namespace fovea::widgets
