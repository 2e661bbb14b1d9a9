// What pathlab says about a render besides its image, as Python data: one sample under the
// inspector (`pathlab inspect --json` as dicts and lists) and the technique maps (`render
// --technique-maps` as arrays).
#pragma once

#include "app/python/renderer.h"

#include <pybind11/pybind11.h>

#include <cstdint>
#include <utility>

namespace pathlab::python {

// pathlab.inspect(scene, settings, pixel, sample): the JSON `pathlab inspect --json` writes for
// the same options, parsed by Python's json module (so the dicts equal the file's).
pybind11::object inspect(const LoadedScene& scene, const PySettings& settings, const pybind11::object& pixel,
                         const pybind11::object& sample);

// pathlab.check(scene, settings, **check options): the dict `pathlab check --json` writes.
pybind11::object check(const LoadedScene& scene, const PySettings& settings, const pybind11::kwargs& kwargs);

// Renderer.technique_maps(): with Settings(technique_maps=L), the maps up to length L.
pybind11::dict techniqueMapsOf(const Renderer& r);
// Renderer.variance_maps(): with Settings(variance_maps=L), each technique's variance of a pass's
// estimate per pixel and the technique with the most (render --variance-maps' images as arrays).
pybind11::dict varianceMapsOf(const Renderer& r);
// Renderer.outliers(): the brightest contributions kept since find_outliers, each replayed, as
// the entries of `pathlab outliers --json`.
pybind11::list outliersOf(const Renderer& r);

// The technique's key in the module's dicts: (s, t), or ("M", s, t) for a merge.
pybind11::object techniqueKey(Technique x);

}  // namespace pathlab::python
