#pragma once
// JSON <-> Python for the module: through Python's own json module, so a document reaches
// Python exactly as `fovea-cli ... --json` prints it (the CLI's printer: non-finite -> null),
// and keyword arguments reach the registry as the CLI's parser would give them.

#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

namespace fovea::python {

// The CLI's printed form of `j` (NaN/inf as null), as Python objects (dict, list, float, ...).
pybind11::object toPython(const nlohmann::json& j);
// Any JSON-serialisable Python object as JSON; TypeError names what cannot be serialised.
nlohmann::json fromPython(const pybind11::handle& o);

}  // namespace fovea::python
