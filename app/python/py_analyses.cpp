// fovea.run / fovea.analyses / fovea.trace: the analysis registry (model/analysis) from Python.
// A study runs on its own thread with the GIL released; the calling thread waits in 50 ms
// slices, reports progress to the callback and checks for signals, so Ctrl-C (KeyboardInterrupt)
// cancels the study cleanly (running samples finish, the exception is raised once it stopped).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <future>
#include <optional>
#include <string>

#include "app/python/py_bindings.h"
#include "app/python/py_json.h"
#include "model/analysis/analysis_json.h"
#include "model/analysis/analysis_registry.h"
#include "model/analysis/study_analyses.h"
#include "model/analysis/trace_fov.h"
#include "model/physics/trace.h"

namespace fovea::python {
namespace py = pybind11;

namespace {

const analysis::AnalysisDefinition& definitionOf(const std::string& id) {
  const auto* def = analysis::findAnalysisDefinition(id);
  if (!def) {
    std::string known;
    for (const auto& d : analysis::analysisRegistry()) known += (known.empty() ? "" : ", ") + d.id;
    throw py::value_error("no analysis \"" + id + "\" (known: " + known + ")");
  }
  return *def;
}

// Keyword arguments as registry values: gaze_from -> "gaze-from"; the defaults fill the rest.
// Problems raise ValueError in the CLI's words ("--gaze-step: must be > 0 deg, got 0").
nlohmann::json valuesOf(const analysis::AnalysisDefinition& def, const py::kwargs& kwargs) {
  nlohmann::json values = analysis::defaultValues(def);
  for (const auto& [key, value] : kwargs) {
    std::string name = py::cast<std::string>(key);
    std::replace(name.begin(), name.end(), '_', '-');
    values[name] = fromPython(value);
  }
  const auto problems = analysis::validateValues(def, values);
  if (!problems.empty()) {
    std::string all;
    for (const auto& p : problems) all += (all.empty() ? "" : "\n") + p.text("--");
    throw py::value_error(all);
  }
  return values;
}

// Runs `compute` off the calling thread (GIL released); progress and Ctrl-C as described above.
nlohmann::json runWatched(const std::function<std::optional<nlohmann::json>(const StudyControl&)>& compute,
                          const py::object& progress, const std::string& what) {
  std::atomic<bool> cancel{false};
  std::atomic<double> fraction{0.0};
  StudyControl control;
  control.cancel = &cancel;
  // The largest fraction reported so far: a study's workers may finish out of order, the
  // user's progress never goes back.
  control.on_progress = [&fraction](double f) {
    double seen = fraction.load(std::memory_order_relaxed);
    while (f > seen && !fraction.compare_exchange_weak(seen, f, std::memory_order_relaxed)) {
    }
  };
  auto result = std::async(std::launch::async, [&] { return compute(control); });
  double reported = -1.0;
  for (;;) {
    std::future_status status;
    {
      py::gil_scoped_release release;
      status = result.wait_for(std::chrono::milliseconds(50));
    }
    if (status == std::future_status::ready) break;
    if (PyErr_CheckSignals() != 0) {  // KeyboardInterrupt (or another handler's exception)
      cancel = true;
      {
        py::gil_scoped_release release;
        result.wait();
      }
      throw py::error_already_set();
    }
    const double f = fraction.load(std::memory_order_relaxed);
    if (!progress.is_none() && f != reported) {
      reported = f;
      try {
        progress(f);
      } catch (...) {  // the callback's exception stops the study like Ctrl-C
        cancel = true;
        py::gil_scoped_release release;
        result.wait();
        throw;
      }
    }
  }
  std::optional<nlohmann::json> out;
  try {
    out = result.get();
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("--") + e.what());  // as the CLI names a refused parameter
  }
  if (!out) throw std::runtime_error(what + " did not complete");
  if (!progress.is_none() && reported != 1.0) progress(1.0);
  return *out;
}

py::object run(const std::string& id, const Scene& scene, const py::object& progress, const py::kwargs& kwargs) {
  const auto& def = definitionOf(id);
  const nlohmann::json values = valuesOf(def, kwargs);
  return toPython(runWatched([&](const StudyControl& c) { return def.run(scene, values, c); }, progress, id));
}

py::dict analyses() {
  py::dict out;
  for (const auto& d : analysis::analysisRegistry()) {
    py::dict params;
    for (const auto& p : d.parameters) {
      py::dict one;
      one["label"] = p.label;
      one["unit"] = p.unit;
      one["default"] = toPython(p.default_value);
      one["help"] = p.help;
      params[py::str(p.name)] = one;
    }
    py::dict entry;
    entry["title"] = d.title;
    entry["description"] = d.description;
    entry["parameters"] = params;
    entry["cli_generated"] = d.cli_generated;  // its fovea-cli options are the registry's parameters
    entry["takes_scene"] = d.takes_scene;
    out[py::str(d.id)] = entry;
  }
  return out;
}

// Zero-copy NumPy views of one field of every ray: the rays stay in the std::vector the trace
// filled (owned by `keep`, a capsule that frees it with the last view), each view strided by
// sizeof(TracedRay). `field` points at the field in the first ray; width 1 gives shape (n,),
// else (n, width) over that many contiguous values (Eigen::Vector3d, std::array<double, 2>).
template <class T>
py::array view(const std::vector<TracedRay>& rays, const T* field, int width, const py::capsule& keep) {
  const auto n = static_cast<py::ssize_t>(rays.size());
  const auto stride = static_cast<py::ssize_t>(sizeof(TracedRay));
  if (width == 1) return py::array_t<T>({n}, {stride}, field, keep);
  return py::array_t<T>({n, py::ssize_t(width)}, {stride, py::ssize_t(sizeof(T))}, field, keep);
}

// The trace document of `fovea-cli trace --json` plus the rays as NumPy arrays (bench frame, mm).
py::object trace(const Scene& scene, const std::optional<std::array<double, 2>>& gaze_deg,
                 const std::array<double, 2>& hoe_shift_mm, const py::kwargs& kwargs) {
  const auto& def = definitionOf("trace");
  py::kwargs all = kwargs;
  if (gaze_deg) all["gaze_yaw"] = (*gaze_deg)[0], all["gaze_pitch"] = (*gaze_deg)[1];
  all["hoe_shift_x"] = hoe_shift_mm[0];
  all["hoe_shift_y"] = hoe_shift_mm[1];
  const nlohmann::json values = valuesOf(def, all);
  TraceOptions o = analysis::traceOptionsFrom(values);
  o.keep_rays = true;
  TraceResult r;
  nlohmann::json doc;
  {
    py::gil_scoped_release release;
    r = traceScene(scene, o);
    doc = traceResultJson(r, o, traceFov(scene, r, o), analysis::traceFovMethodFrom(values));
  }
  py::dict out = toPython(doc);
  // The rays move to the heap, owned by the capsule the views share (no copy of any ray).
  auto* owned = new std::vector<TracedRay>(std::move(r.ray_list));
  const py::capsule keep(owned, [](void* p) { delete static_cast<std::vector<TracedRay>*>(p); });
  const std::vector<TracedRay>& rays = *owned;
  // An empty trace has no first ray to point at; its views are empty all the same.
  static const TracedRay none;
  const TracedRay& first = rays.empty() ? none : rays.front();
  py::dict arrays;
  arrays["source_mm"] = view(rays, first.source.data(), 3, keep);
  arrays["hoe_point_mm"] = view(rays, first.hoe_point.data(), 3, keep);
  arrays["out_direction"] = view(rays, first.out_direction.data(), 3, keep);
  arrays["field_deg"] = view(rays, first.field_deg.data(), 2, keep);
  arrays["wavelength_nm"] = view(rays, &first.wavelength_nm, 1, keep);
  arrays["efficiency"] = view(rays, &first.efficiency, 1, keep);
  arrays["pupil_radius_mm"] = view(rays, &first.pupil_radius_mm, 1, keep);
  arrays["hits_hoe"] = view(rays, &first.hits_hoe, 1, keep);
  arrays["in_pupil"] = view(rays, &first.in_pupil, 1, keep);
  out["ray_arrays"] = arrays;
  return out;
}

}  // namespace

void bindAnalyses(py::module_& m) {
  m.def("run", &run, py::arg("analysis"), py::arg("scene"), py::kw_only(), py::arg("progress") = py::none(),
        "Run a registered analysis (the `fovea-cli ANALYSIS SCENE ... --json` document as Python objects).\n"
        "Parameters by the registry's names with '_' for '-': fovea.run(\"sweep\", s, gaze_from=-20, gaze_to=20).\n"
        "progress(fraction) is called from the calling thread; Ctrl-C cancels the study cleanly.");
  m.def("analyses", &analyses,
        "Every registered analysis: title, description, parameters (label, unit, default, help).");
  m.def("trace", &trace, py::arg("scene"), py::arg("gaze_deg") = py::none(),
        py::arg("hoe_shift_mm") = std::array<double, 2>{0.0, 0.0},
        "Trace the projector through the HOE into the eye: the `fovea-cli trace --json` document, and the rays "
        "as NumPy arrays in ['ray_arrays'] (source_mm, hoe_point_mm, out_direction, field_deg, wavelength_nm, "
        "efficiency, pupil_radius_mm, hits_hoe, in_pupil). Other trace parameters as keywords (rays=4000, ...).");
}

}  // namespace fovea::python
