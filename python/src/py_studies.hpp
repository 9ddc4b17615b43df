#pragma once

#include <pybind11/pybind11.h>

namespace yuxi::python {

void bind_studies(pybind11::module_& m);

} // namespace yuxi::python
