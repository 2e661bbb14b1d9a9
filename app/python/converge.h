// pathlab.converge: configurations rendered progressively with their error recorded at
// geometrically spaced checkpoints (runConvergence, what `pathlab converge` measures), returned as
// NumPy curves.
#pragma once

#include "app/python/renderer.h"

#include <pybind11/pybind11.h>

#include <optional>

namespace pathlab::python {

// `configs`: a Settings, a list of them (labelled by their options) or a dict {label: Settings};
// `reference`: an image array or an .exr/.pfm path, or None (the error then only as the two-buffer
// estimate); `mask`: an (height, width) array, the pixels where it is non-zero.
pybind11::dict converge(const LoadedScene& scene, const pybind11::object& configs, std::optional<double> seconds,
                        const pybind11::object& spp, const pybind11::object& reference, double factor,
                        const std::string& clock, const pybind11::object& mask);

}  // namespace pathlab::python
