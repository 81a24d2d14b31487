#pragma once
// The Bench dock's axes: one row per stage binding (element position in the scene's frame,
// state, jog buttons, Home, a go-to field), the jog step and speed, the selected axis. The
// focus axis (foveal_display z, model/physics/focus_stage.h) also shows the foveal image's
// distance from the pupil in cm and dioptres.
//
// Typed targets are never changed by the field: it takes any number, and a target outside
// the binding's soft limits is refused with the reason in the preferred units and in the
// row's frame (element coordinates); nothing is sent. After an emergency stop the axes that
// were moving report "stopped" with the position where they stopped, in the row's frame.
//
// Threads: commands run on the axis workers; results come back as queued calls.
#include <QGroupBox>

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "devices/bench/live_bench.h"
#include "model/physics/focus_stage.h"

class QButtonGroup;
class QDoubleSpinBox;
class QGridLayout;
class QLabel;
class QPushButton;
class QRadioButton;

namespace fovea::widgets {

class AxisTable : public QGroupBox {
  Q_OBJECT
 public:
  explicit AxisTable(QWidget* parent = nullptr);

  void setBench(devices::LiveBench* live);  // nullptr: no rows
  // The scene's combiner, for the focus axis's image distance (before setBench; nullopt: none).
  void setFocusModel(std::optional<FocusStageModel> model) { focus_model_ = model; }
  void refresh();  // readouts from the axis snapshots

  void jog(const QString& axis_key, int direction);  // +1 forward, -1 reverse
  void goTo(const QString& axis_key, double element_value);
  void homeAll();
  // Call right after the bench's emergencyStopAll(): the rows that were moving say "stopped
  // at X" (the row's frame) once they stand, and each is reported.
  void noteEmergencyStop();
  // A note in the axis's state column ("refused: …", "stopped at …") that stays until the next
  // command of that row; the full text in its tooltip. Empty: none.
  void setRowNote(const QString& axis_key, const QString& note, const QString& message, bool error);
  QString stateText(const QString& axis_key) const;

  double stepSize() const;
  void setStepSize(double step);
  void setSpeed(double speed);
  void scaleStep(double factor);
  void setSelectedAxis(const QString& key);
  QString selectedAxis() const;
  void selectNext(int delta);  // +1 down, -1 up (wraps)
  bool hasRows() const { return !rows_.empty(); }
  std::optional<double> axisPosition(const QString& key) const;

  // The jog controls (step, speed, key help) live in the panel's layout under the table.
  QWidget* jogControls() const { return jog_controls_; }

 signals:
  void report(const QString& text, bool error);

 private:
  struct Row {
    devices::AxisWorker* worker = nullptr;
    QString key, unit;
    QRadioButton* select = nullptr;
    QLabel *name = nullptr, *position = nullptr, *state = nullptr;
    QPushButton *reverse = nullptr, *forward = nullptr, *home = nullptr, *go = nullptr;
    QDoubleSpinBox* target = nullptr;
    // Commands submitted and not yet reported back on the GUI thread.
    std::shared_ptr<std::atomic<int>> pending = std::make_shared<std::atomic<int>>(0);
    // Commands submitted and not yet finished on the worker thread: the jog throttle counts these,
    // not `pending`, whose count-down waits for the GUI thread's queue (a jog that has finished but
    // whose report is still queued must not block the next one).
    std::shared_ptr<std::atomic<int>> unfinished = std::make_shared<std::atomic<int>>(0);
    QString note, note_tip;  // shown instead of the computed state while set
    bool note_error = false;
    bool stop_pending = false;  // Esc while it moved: say where it stopped once it stands
    bool focus = false;         // the focus axis: the image distance beside the position
    std::string seen_error;     // the snapshot's last error already reported
  };
  void refuse(Row& row, const QString& what, double value);
  void setNote(Row& row, const QString& note, const QString& message, bool error);
  void clearRows();
  void submit(Row& row, const QString& what, std::function<void(devices::Stage&)> command);
  QString stageFrameHint(const Row& row, const QString& error) const;
  Row* row(const QString& key);
  const Row* row(const QString& key) const;

  devices::LiveBench* live_ = nullptr;
  std::optional<FocusStageModel> focus_model_;
  std::vector<Row> rows_;
  QGridLayout* grid_ = nullptr;
  QButtonGroup* select_group_ = nullptr;
  QWidget* jog_controls_ = nullptr;
  QDoubleSpinBox *step_ = nullptr, *speed_ = nullptr;
  // Counts emergency stops; a command that fails after one started was stopped by the user.
  std::shared_ptr<std::atomic<int>> stops_ = std::make_shared<std::atomic<int>>(0);
};

// "12.500 mm" / "20.00°" in the preferred display units (model values in mm or deg).
QString formatAxisValue(double value, const QString& unit);
// The focus axis's image: "50.0 cm · 2.00 D" for an image 500 mm from the pupil ("∞" beyond).
QString formatFocusImage(const FocusStageModel& model, double axis_mm);

}  // namespace fovea::widgets
