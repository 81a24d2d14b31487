#pragma once
// The studio's default dock arrangement, sized to the window so that it fits a 1366x768
// screen as well as a 1920x1080 one: the 3-D view in the centre takes most of the window,
// the docks sit in tab groups (left: scene tree over gaze/rays; right: properties,
// analyses and bench over retina, grating vectors and preview; bottom: messages and plots).
// View ▸ Reset Layout calls applyDefaultDockLayout() again.

class QDockWidget;
class QMainWindow;
class QWidget;

namespace fovea::studio {

// Puts every known dock (by object name) into its default tab group and sizes the areas
// in proportion to the window. Docks that do not exist are skipped; unknown docks stay.
void applyDefaultDockLayout(QMainWindow* window);

// A dock's content wrapped in a frameless, resizable scroll area, so that a panel taller
// than the space left to it scrolls instead of forcing the window taller than the screen.
// A panel that has a scroll area of its own is returned as it is (one scroll area per dock).
QWidget* scrollableDockContent(QWidget* panel);

// Widens the column of `dock` (a side dock) so its panel shows without a horizontal scroll bar:
// to the panel's size hint plus the vertical scroll bar, as far as the central widget (the 3-D
// view) keeps 30 % of the window's width; never narrower than it is. For panels whose rows are wide (the Bench
// dock's axis rows with their jog, home and go-to controls).
void widenDockToFit(QMainWindow* window, QDockWidget* dock);

}  // namespace fovea::studio
