#pragma once
// The studio's preferences, persisted with QSettings ("preferences/..."): how lengths and
// angles are displayed (plots, analysis summaries, reports), the default ray count of the
// analyses, the colour theme, the autosave interval and the 3-D view's resolution while dragging. One shared instance;
// widgets follow changes through changed(). Values are always stored in the model's units (mm, deg); only their display
// is converted.

#include <QDialog>
#include <QObject>
#include <QString>

class QComboBox;
class QSpinBox;
class QApplication;

namespace fovea::widgets {

enum class LengthUnit { Millimetre, Micrometre, Inch };
enum class AngleUnit { Degree, Radian };
enum class Theme { System, Light, Dark };

struct PreferenceValues {
  LengthUnit length = LengthUnit::Millimetre;
  AngleUnit angle = AngleUnit::Degree;
  int defaultRays = 1500;  // rays per wavelength of the report dialog (50 .. 1e6); analyses: the registry's
  Theme theme = Theme::System;
  int autosaveSeconds = 5;  // 1 .. 600
  // The 3-D view's resolution while a hand drags, % of full in each direction (25 .. 100):
  // drag frames on a software renderer cost per pixel (viz::SceneView::setDragRenderScale).
  int dragResolutionPercent = 50;
  bool operator==(const PreferenceValues&) const = default;
};

// Display conversion of the model's units.
struct DisplayUnits {
  LengthUnit lengthUnit = LengthUnit::Millimetre;
  AngleUnit angleUnit = AngleUnit::Degree;
  double lengthFromMm(double mm) const;
  double angleFromDeg(double deg) const;
  double lengthToMm(double shown) const;                 // inverse of lengthFromMm
  double angleToDeg(double shown) const;                 // inverse of angleFromDeg
  QString lengthSymbol() const;                          // "mm", "µm", "in"
  QString angleSymbol() const;                           // "deg", "rad"
  QString length(double mm, int significant = 4) const;  // "12.5 mm"
  QString angle(double deg, int significant = 4) const;  // "20 deg"
  bool operator==(const DisplayUnits&) const = default;
};

class Preferences : public QObject {
  Q_OBJECT
 public:
  static Preferences& instance();

  const PreferenceValues& values() const { return values_; }
  DisplayUnits units() const { return {values_.length, values_.angle}; }
  // Applies (theme included) and, when persistent, writes them to QSettings.
  void setValues(const PreferenceValues& v);
  // Reads QSettings (missing or invalid entries keep their defaults) and enables writing.
  void load();
  void setPersistent(bool on) { persistent_ = on; }
  static void applyTheme(Theme theme);

  static QString lengthUnitKey(LengthUnit u);
  static QString angleUnitKey(AngleUnit u);
  static QString themeKey(Theme t);

 signals:
  void changed();

 private:
  Preferences() = default;
  PreferenceValues values_;
  bool persistent_ = false;
};

class PreferencesDialog : public QDialog {
  Q_OBJECT
 public:
  explicit PreferencesDialog(QWidget* parent = nullptr);
  PreferenceValues chosen() const;
  void accept() override;  // applies through Preferences::setValues

 private:
  QComboBox* length_ = nullptr;
  QComboBox* angle_ = nullptr;
  QSpinBox* rays_ = nullptr;
  QComboBox* theme_ = nullptr;
  QSpinBox* autosave_ = nullptr;
  QSpinBox* dragResolution_ = nullptr;
};

}  // namespace fovea::widgets
