// The compiled part of the Python module `yuxi` (python/yuxi/__init__.py wraps it).
#include "domain/mpi_session.hpp"
#include "py_coarse_grain.hpp"
#include "py_scene.hpp"
#include "py_simulation.hpp"
#include "py_studies.hpp"
#include "run/device_run.hpp"

#include <pybind11/pybind11.h>

PYBIND11_MODULE(_yuxi, m) {
  m.doc() = "yuxi: 3-D soft-sphere DEM for granular matter (the compiled core)";
  yuxi::python::bind_scene(m);
  yuxi::python::bind_simulation(m);
  yuxi::python::bind_studies(m);
  yuxi::python::bind_coarse_grain(m);
  // MPI for the interpreter's lifetime: joined where mpi4py started it (yuxi/__init__.py imports
  // mpi4py first when it is there, and mpi4py finishes it), else started here and finished at
  // exit, after the Python layer has closed every simulation.
  static auto* session = new yuxi::MpiSession();
  m.def("_finish_mpi", [] {
    delete session;
    session = nullptr;
  });
  m.attr("_mpi_started_here") = session->started_here();
  m.attr("has_cuda") = yuxi::build_has_cuda();
}
