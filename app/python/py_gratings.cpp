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

// One input column of the broadcast batch. A zero-stride broadcast (a scalar such as the default
// absorption_per_mm = 0.0, or an array broadcast along every axis) is read as a constant instead
// of being copied out to n elements; everything else is a C-contiguous view (no copy when the
// caller's array is already contiguous float64).
struct Column {
  Array keep;  // owns the data `p` points into
  const double* p = nullptr;
  bool constant = false;
  double at(std::size_t i) const { return constant ? p[0] : p[i]; }
};

struct Batch {
  std::vector<Column> in;          // one per kInputs
  std::vector<py::ssize_t> shape;  // the broadcast shape
  std::size_t n = 0;
  Polarization polarization = Polarization::S;
};

bool allStridesZero(const py::array& a) {
  for (py::ssize_t d = 0; d < a.ndim(); ++d)
    if (a.strides(d) != 0 && a.shape(d) > 1) return false;
  return true;
}

Batch batchOf(const std::vector<py::object>& values, const std::string& polarization) {
  const auto pol = parsePolarization(polarization);
  if (!pol) throw py::value_error("polarization: must be s, p or unpolarized, got \"" + polarization + "\"");
  py::object np = py::module_::import("numpy");
  py::tuple args(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) args[i] = np.attr("asarray")(values[i], "float64");
  const py::list broadcast = np.attr("broadcast_arrays")(*args);
  Batch b;
  b.polarization = *pol;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const py::array a = broadcast[k];
    Column c;
    c.constant = allStridesZero(a);
    // A constant column is its original (possibly 0-d) array's first element.
    c.keep = Array::ensure(c.constant ? np.attr("ascontiguousarray")(args[k]) : np.attr("ascontiguousarray")(a));
    c.p = c.keep.data();
    b.in.push_back(std::move(c));
  }
  // The shape before ascontiguousarray (which makes a 0-d array 1-d).
  const py::array first = broadcast[0];
  b.shape.assign(first.shape(), first.shape() + first.ndim());
  b.n = static_cast<std::size_t>(first.size());
  return b;
}

// Fills the reusable request `r` with element i (its model/orders/slices untouched): no
// per-element construction of the request's strings.
void fillRequest(const Batch& b, std::size_t i, GratingRequest& r) {
  r.grating.film.n0 = b.in[0].at(i);
  r.grating.film.n1 = b.in[1].at(i);
  r.grating.film.thickness_um = b.in[2].at(i);
  r.grating.period_nm = b.in[3].at(i);
  r.grating.slant_deg = b.in[4].at(i);
  r.grating.probe_deg = b.in[5].at(i);
  r.grating.wavelength_nm = b.in[6].at(i);
  r.absorption_per_mm = b.in[7].at(i);
  r.grating.polarization = b.polarization;
}

// The first invalid element of a batch, found inside the GIL-free loop: the loop stops there and
// the caller raises ValueError naming its index and the key, in the words of `fovea-cli grating
// --batch` (nothing is returned for a batch with a bad element, as before).
struct FirstError {
  std::size_t index = 0;
  std::string message;
};

[[noreturn]] void raise(const FirstError& e) {
  throw py::value_error("grating " + std::to_string(e.index) + ": " + e.message);
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
  Outputs o(b, 5);  // efficiency, zero_order, nu, xi, diffracted_deg
  py::array_t<bool> reflection(b.shape);
  bool* refl = reflection.mutable_data();
  std::optional<FirstError> bad;
  {
    py::gil_scoped_release release;
    GratingRequest r;
    for (std::size_t i = 0; i < b.n; ++i) {
      fillRequest(b, i, r);
      if (auto e = validateGratingRequest(r, /*flags=*/false)) {
        bad = FirstError{i, std::move(e->message)};
        break;
      }
      const PlanarDiffraction d = diffractPlanar(planarGratingOf(r));  // as kogelnikGratingJson
      o.data[0][i] = d.grating.kogelnik.efficiency;
      o.data[1][i] = d.grating.kogelnik.zero_order;
      o.data[2][i] = d.grating.kogelnik.nu;
      o.data[3][i] = d.grating.kogelnik.xi;
      o.data[4][i] = d.diffracted_deg ? *d.diffracted_deg : std::numeric_limits<double>::quiet_NaN();
      refl[i] = d.grating.reflection();
    }
  }
  if (bad) raise(*bad);
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
  Outputs o(b, 3);  // efficiency, zero_order, kogelnik_efficiency
  std::optional<FirstError> bad;
  {
    py::gil_scoped_release release;
    GratingRequest r;
    r.model = "rcwa";
    r.orders = orders;
    r.slices = slices;
    // Every element validated before any is computed (an RCWA point costs milliseconds).
    for (std::size_t i = 0; i < b.n && !bad; ++i) {
      fillRequest(b, i, r);
      if (auto e = validateGratingRequest(r, /*flags=*/false)) bad = FirstError{i, std::move(e->message)};
    }
    for (std::size_t i = 0; i < b.n && !bad; ++i) {
      fillRequest(b, i, r);
      nlohmann::json j;
      try {
        j = rigorous::rcwaGratingJson(r);
      } catch (const std::exception& e) {
        bad = FirstError{i, e.what()};
        break;
      }
      o.data[0][i] = j.at("efficiency").get<double>();
      o.data[1][i] = j.at("zero_order").get<double>();
      o.data[2][i] = j.value("kogelnik_efficiency", std::numeric_limits<double>::quiet_NaN());
    }
  }
  if (bad) raise(*bad);
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
