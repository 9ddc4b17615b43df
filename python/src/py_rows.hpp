// A numpy array of n rows of `width` values each (one dimension where width is 1), copied from
// a column filled row by row: the form the contact and clump tables hand to Python.
#pragma once

#include <cstring>
#include <pybind11/numpy.h>
#include <vector>

namespace yuxi::python {

template <class T>
pybind11::array_t<T> rows_of(const std::vector<T>& values, pybind11::ssize_t n,
                             pybind11::ssize_t width) {
  pybind11::array_t<T> a = width == 1 ? pybind11::array_t<T>(n) : pybind11::array_t<T>({n, width});
  if (n > 0) std::memcpy(a.mutable_data(), values.data(), values.size() * sizeof(T));
  return a;
}

} // namespace yuxi::python
