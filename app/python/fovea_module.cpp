// The `fovea` Python module: the studio's model (model/, no Qt, no VTK) for notebooks and
// scripts. Every computation releases the GIL. docs/python.md; stubs in fovea.pyi.
#include <pybind11/pybind11.h>

#include "app/python/py_bindings.h"
#include "fovea/version.h"
#include "model/memory_policy.h"

PYBIND11_MODULE(fovea, m) {
  m.doc() = "Foveated AR Studio's model: scenes, traces, the registered analyses and grating physics.";
  m.attr("__version__") = FOVEA_VERSION_STRING;
  // Large buffers reused between renders, as in fovea-cli (model/memory_policy.h): the
  // interpreter keeps its high-water mark of memory.
  fovea::keepFreedMemoryForReuse();
  fovea::python::bindScene(m);
  fovea::python::bindAnalyses(m);
  fovea::python::bindGratings(m);
}
