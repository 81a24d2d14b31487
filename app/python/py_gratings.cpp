// fovea.kogelnik / fovea.rcwa: planar volume gratings over NumPy arrays (broadcast like NumPy),
// each element the question `fovea-cli grating` answers (model/physics/grating_request.h), the
// loop in C++ with the GIL released: no per-element Python overhead.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "app/python/py_bindings.h"
#include "model/physics/grating_request.h"
#include "model/rigorous/rcwa_grating_request.h"

namespace fovea::python {
namespace py = pybind11;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
constexpr const char* kInputs[] = {"n0",        "n1",        "thickness_um",  "period_nm",
                                   "slant_deg", "probe_deg", "wavelength_nm", "absorption_per_mm"};
constexpr std::size_t kInputCount = std::size(kInputs);

struct Batch {
  std::vector<Array> in;           // broadcast, contiguous, one per kInputs
  std::vector<py::ssize_t> shape;  // the broadcast shape
  std::size_t n = 0;
  Polarization polarization = Polarization::S;
};

Batch batchOf(const std::vector<py::object>& values, const std::string& polarization) {
  const auto pol = parsePolarization(polarization);
  if (!pol) throw py::value_error("polarization: must be s, p or unpolarized, got \"" + polarization + "\"");
  py::object np = py::module_::import("numpy");
  py::tuple args(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) args[i] = np.attr("asarray")(values[i], "float64");
  const py::list broadcast = np.attr("broadcast_arrays")(*args);
  Batch b;
  b.polarization = *pol;
  for (const auto& a : broadcast) b.in.push_back(Array::ensure(np.attr("ascontiguousarray")(a)));
  // The shape before ascontiguousarray (which makes a 0-d array 1-d).
  const py::array first = broadcast[0];
  b.shape.assign(first.shape(), first.shape() + first.ndim());
  b.n = static_cast<std::size_t>(first.size());
  return b;
}

GratingRequest requestAt(const Batch& b, std::size_t i) {
  GratingRequest r;
  auto v = [&](std::size_t k) { return b.in[k].data()[i]; };
  r.grating.film.n0 = v(0);
  r.grating.film.n1 = v(1);
  r.grating.film.thickness_um = v(2);
  r.grating.period_nm = v(3);
  r.grating.slant_deg = v(4);
  r.grating.probe_deg = v(5);
  r.grating.wavelength_nm = v(6);
  r.absorption_per_mm = v(7);
  r.grating.polarization = b.polarization;
  return r;
}

// Every element validated before any is computed: the first bad one raises ValueError naming
// its index and the key, in the words of `fovea-cli grating --batch`.
void validate(const Batch& b) {
  for (std::size_t i = 0; i < b.n; ++i)
    if (const auto e = validateGratingRequest(requestAt(b, i), /*flags=*/false))
      throw py::value_error("grating " + std::to_string(i) + ": " + e->message);
}

// The broadcast shape, also for scalars (NumPy's 0-d arrays, as numpy.add(1.0, 2.0) gives).
py::object shaped(const py::array& a, const std::vector<py::ssize_t>& shape) {
  return a.attr("reshape")(py::tuple(py::cast(shape)));
}

struct Outputs {
  std::vector<Array> arrays;
  std::vector<double*> data;
  Outputs(const Batch& b, std::size_t count) {
    for (std::size_t k = 0; k < count; ++k) {
      arrays.emplace_back(b.shape);
      data.push_back(arrays.back().mutable_data());
    }
  }
};

py::dict kogelnikBatch(py::object n0, py::object n1, py::object thickness_um, py::object period_nm,
                       py::object slant_deg, py::object probe_deg, py::object wavelength_nm,
                       const std::string& polarization, py::object absorption_per_mm) {
  const Batch b =
      batchOf({n0, n1, thickness_um, period_nm, slant_deg, probe_deg, wavelength_nm, absorption_per_mm}, polarization);
  validate(b);
  Outputs o(b, 5);  // efficiency, zero_order, nu, xi, diffracted_deg
  py::array_t<bool> reflection(b.shape);
  bool* refl = reflection.mutable_data();
  {
    py::gil_scoped_release release;
    for (std::size_t i = 0; i < b.n; ++i) {
      const PlanarDiffraction d = diffractPlanar(planarGratingOf(requestAt(b, i)));  // as kogelnikGratingJson
      o.data[0][i] = d.grating.kogelnik.efficiency;
      o.data[1][i] = d.grating.kogelnik.zero_order;
      o.data[2][i] = d.grating.kogelnik.nu;
      o.data[3][i] = d.grating.kogelnik.xi;
      o.data[4][i] = d.diffracted_deg ? *d.diffracted_deg : std::numeric_limits<double>::quiet_NaN();
      refl[i] = d.grating.reflection();
    }
  }
  py::dict out;
  out["efficiency"] = shaped(o.arrays[0], b.shape);
  out["zero_order"] = shaped(o.arrays[1], b.shape);
  out["nu"] = shaped(o.arrays[2], b.shape);
  out["xi"] = shaped(o.arrays[3], b.shape);
  out["diffracted_deg"] =
      shaped(o.arrays[4], b.shape);  // NaN where the diffracted wave is evanescent (null in the CLI)
  out["reflection"] = shaped(reflection, b.shape);
  return out;
}

py::dict rcwaBatch(py::object n0, py::object n1, py::object thickness_um, py::object period_nm, py::object slant_deg,
                   py::object probe_deg, py::object wavelength_nm, const std::string& polarization,
                   py::object absorption_per_mm, std::optional<int> orders, std::optional<int> slices) {
  const Batch b =
      batchOf({n0, n1, thickness_um, period_nm, slant_deg, probe_deg, wavelength_nm, absorption_per_mm}, polarization);
  validate(b);
  Outputs o(b, 3);  // efficiency, zero_order, kogelnik_efficiency
  {
    py::gil_scoped_release release;
    for (std::size_t i = 0; i < b.n; ++i) {
      GratingRequest r = requestAt(b, i);
      r.model = "rcwa";
      r.orders = orders;
      r.slices = slices;
      nlohmann::json j;
      try {
        j = rigorous::rcwaGratingJson(r);
      } catch (const std::exception& e) {
        py::gil_scoped_acquire acquire;
        throw py::value_error("grating " + std::to_string(i) + ": " + e.what());
      }
      o.data[0][i] = j.at("efficiency").get<double>();
      o.data[1][i] = j.at("zero_order").get<double>();
      o.data[2][i] = j.value("kogelnik_efficiency", std::numeric_limits<double>::quiet_NaN());
    }
  }
  py::dict out;
  out["efficiency"] = shaped(o.arrays[0], b.shape);
  out["zero_order"] = shaped(o.arrays[1], b.shape);
  out["kogelnik_efficiency"] = shaped(o.arrays[2], b.shape);
  return out;
}

}  // namespace

void bindGratings(py::module_& m) {
  static_assert(kInputCount == 8);
  m.def("kogelnik", &kogelnikBatch, py::arg("n0"), py::arg("n1"), py::arg("thickness_um"), py::arg("period_nm"),
        py::arg("slant_deg"), py::arg("probe_deg"), py::arg("wavelength_nm"), py::kw_only(),
        py::arg("polarization") = "s", py::arg("absorption_per_mm") = 0.0,
        "Kogelnik coupled-wave diffraction of planar volume gratings, element-wise over NumPy arrays (broadcast):\n"
        "{'efficiency', 'zero_order', 'nu', 'xi', 'diffracted_deg', 'reflection'} arrays of the broadcast shape,\n"
        "each element what `fovea-cli grating --json` answers for it.");
  m.def("rcwa", &rcwaBatch, py::arg("n0"), py::arg("n1"), py::arg("thickness_um"), py::arg("period_nm"),
        py::arg("slant_deg"), py::arg("probe_deg"), py::arg("wavelength_nm"), py::kw_only(),
        py::arg("polarization") = "s", py::arg("absorption_per_mm") = 0.0, py::arg("orders") = py::none(),
        py::arg("slices") = py::none(),
        "Rigorous coupled-wave analysis of the same gratings (`fovea-cli grating --model rcwa`): "
        "{'efficiency', 'zero_order', 'kogelnik_efficiency'} arrays.");
}

}  // namespace fovea::python
