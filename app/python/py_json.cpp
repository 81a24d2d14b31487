#include "app/python/py_json.h"

#include <cmath>

namespace fovea::python {
namespace py = pybind11;

namespace {
// As app/cli/cli_common.cpp prints: a non-finite number is null (JSON has no NaN).
nlohmann::json printable(const nlohmann::json& j) {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) return nullptr;
  if (j.is_array() || j.is_object()) {
    nlohmann::json out = j;
    for (auto& v : out) v = printable(v);
    return out;
  }
  return j;
}
}  // namespace

py::object toPython(const nlohmann::json& j) {
  // Looked up per call (sys.modules makes it cheap): a static py::object would outlive the
  // interpreter and crash its finalisation.
  return py::module_::import("json").attr("loads")(printable(j).dump());
}

nlohmann::json fromPython(const py::handle& o) {
  const py::object dumps = py::module_::import("json").attr("dumps");
  // allow_nan=False: a NaN argument is refused here, as the CLI refuses "nan" for a number.
  const std::string text = py::cast<std::string>(dumps(o, py::arg("allow_nan") = false));
  return nlohmann::json::parse(text);
}

}  // namespace fovea::python
