// fovea-studio: placeholder entry point; the main window lands with the foundation GUI.
#include <QApplication>
#include <QLabel>

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  QLabel label("Foveated AR Studio");
  label.show();
  return 0;
}
