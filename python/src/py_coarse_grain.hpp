#pragma once

#include <pybind11/pybind11.h>

namespace yuxi::python {

// _yuxi.coarse_grain: continuum fields from arrays of grains and contacts (analysis/
// coarse_grain.hpp); yuxi.coarse_grain (python/yuxi/__init__.py) feeds it a simulation's or a
// snapshot's arrays.
void bind_coarse_grain(pybind11::module_& m);

} // namespace yuxi::python
