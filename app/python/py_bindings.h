#pragma once
// The pieces of the `fovea` Python module (app/python/fovea_module.cpp), one file each.

#include <pybind11/pybind11.h>

namespace fovea::python {

void bindScene(pybind11::module_& m);     // py_scene.cpp: fovea.Scene
void bindAnalyses(pybind11::module_& m);  // py_analyses.cpp: fovea.run, fovea.analyses, fovea.trace
void bindGratings(pybind11::module_& m);  // py_gratings.cpp: fovea.kogelnik, fovea.rcwa

}  // namespace fovea::python
