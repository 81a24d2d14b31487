// fovea.Scene: a scene file's model (model/scene) — load, the embedded prototype, save, number
// fields by their JSON paths, validation with the messages of `fovea-cli validate`.
#include "app/python/py_bindings.h"

#include <pybind11/stl.h>

#include <string>
#include <variant>
#include <vector>

#include "app/embedded_scene.h"
#include "app/python/py_json.h"
#include "model/scene/scene_fields.h"
#include "model/scene/scene_io.h"

namespace fovea::python {
namespace py = pybind11;

namespace {

std::string joined(const std::vector<std::string>& lines) {
  std::string all;
  for (const auto& e : lines) all += (all.empty() ? "" : "\n") + e;
  return all;
}

// As `fovea-cli` loads a scene (app/cli/cli_common.cpp): every problem, one per line.
Scene sceneOf(SceneLoadResult r) {
  if (!r.ok()) throw py::value_error(joined(r.errors));
  return *r.scene;
}

py::object numberValue(Scene& scene, const std::string& path) {
  std::variant<double*, int*> ref;
  try {
    ref = numberAt(scene, path);
  } catch (const std::invalid_argument& e) {
    throw py::key_error(e.what());
  }
  if (auto* d = std::get_if<double*>(&ref)) return py::float_(**d);
  return py::int_(*std::get<int*>(ref));
}

// Sets the number at `path`; a value the format refuses leaves the scene unchanged and raises
// ValueError with the validator's message ("hoe_layers[1].n1: must be < n0 (1.5), got 1.6").
void setNumber(Scene& scene, const std::string& path, const py::object& value) {
  Scene edited = scene;
  std::variant<double*, int*> ref;
  try {
    ref = numberAt(edited, path);
  } catch (const std::invalid_argument& e) {
    throw py::key_error(e.what());
  }
  if (auto* d = std::get_if<double*>(&ref)) {
    **d = py::cast<double>(value);
  } else {
    const double v = py::cast<double>(value);
    if (v != static_cast<double>(static_cast<long long>(v)))
      throw py::value_error(path + ": must be an integer, got " + py::cast<std::string>(py::repr(value)));
    *std::get<int*>(ref) = static_cast<int>(v);
  }
  const auto problems = validateScene(edited);
  if (!problems.empty()) throw py::value_error(joined(problems));
  scene = std::move(edited);
}

}  // namespace

void bindScene(py::module_& m) {
  py::class_<Scene>(m, "Scene", "A bench scene (docs/scene-format.md): what a scene file holds.")
      .def_static(
          "load", [](const std::string& path) { return sceneOf(loadSceneFile(path)); }, py::arg("path"),
          "Load a scene file; ValueError lists every problem, as `fovea-cli validate` does.")
      .def_static(
          "embedded", [] { return sceneOf(parseScene(embeddedDefaultSceneJson(), std::string(kEmbeddedSceneName))); },
          "The default prototype bench compiled into the studio (resources/scenes/prototype-bench.json).")
      .def_static(
          "from_json", [](const std::string& text) { return sceneOf(parseScene(text, "<json>")); }, py::arg("text"),
          "A scene from the text of a scene file.")
      .def(
          "save", [](const Scene& s, const std::string& path) { saveSceneFileAtomic(s, path); }, py::arg("path"),
          "Write the scene file atomically (the old file stays whole if writing fails).")
      .def(
          "to_json", [](const Scene& s) { return serializeScene(s); }, "The scene file's text.")
      .def(
          "validate", [](const Scene& s) { return validateScene(s); }, "Every problem of the scene; empty when valid.")
      .def(
          "summary", [](const Scene& s) { return sceneSummary(s); }, "One line: layers, HOE, projector, eye.")
      .def("__getitem__", &numberValue, py::arg("path"), "The number at a JSON path: scene[\"eye.relief_mm\"].")
      .def("__setitem__", &setNumber, py::arg("path"), py::arg("value"),
           "Set the number at a JSON path; ValueError (scene unchanged) when the format refuses it.")
      .def("copy", [](const Scene& s) { return Scene(s); })
      .def("__repr__", [](const Scene& s) { return "<fovea.Scene " + sceneSummary(s) + ">"; });
}

}  // namespace fovea::python
