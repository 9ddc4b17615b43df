#include "py_clumps.hpp"

#include "py_rows.hpp"

#include <pybind11/numpy.h>
#include <vector>

namespace py = pybind11;
using namespace pybind11::literals;

namespace yuxi::python {

py::dict clump_arrays(const Simulation& sim) {
  const std::vector<ClumpBody>& bodies = sim.clumps();
  std::vector<std::int64_t> id, shape, members;
  std::vector<double> position, velocity, orientation, omega, mass, inertia, force, torque;
  const auto add = [](std::vector<double>& c, const Vec3& v) {
    c.insert(c.end(), {v.x, v.y, v.z});
  };
  for (const ClumpBody& b : bodies) {
    id.push_back(b.id);
    shape.push_back(b.shape);
    members.push_back(static_cast<std::int64_t>(b.members.size()));
    add(position, b.x);
    add(velocity, b.v);
    orientation.insert(orientation.end(), {b.q.w, b.q.x, b.q.y, b.q.z});
    add(omega, b.angular_velocity());
    mass.push_back(b.mass);
    add(inertia, b.inertia);
    add(force, b.force);
    add(torque, b.torque);
  }
  const auto n = static_cast<py::ssize_t>(bodies.size());
  return py::dict("id"_a = rows_of(id, n, 1), "shape"_a = rows_of(shape, n, 1),
                  "position"_a = rows_of(position, n, 3), "velocity"_a = rows_of(velocity, n, 3),
                  "orientation"_a = rows_of(orientation, n, 4),
                  "angular_velocity"_a = rows_of(omega, n, 3), "mass"_a = rows_of(mass, n, 1),
                  "inertia"_a = rows_of(inertia, n, 3), "members"_a = rows_of(members, n, 1),
                  "force"_a = rows_of(force, n, 3), "torque"_a = rows_of(torque, n, 3));
}

} // namespace yuxi::python
