#include "py_clumps.hpp"

#include "py_rows.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
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

namespace {

// Rows of `width` values, as many as `n` (n < 0: any), from an array of that shape.
std::vector<double> rows(const DoubleRows& a, py::ssize_t width, py::ssize_t& n, const char* what) {
  const bool fits = width == 1 ? a.ndim() == 1 : a.ndim() == 2 && a.shape(1) == width;
  if (!fits || (n >= 0 && a.shape(0) != n))
    throw py::value_error(
        n >= 0 ? fmt::format("add_clumps: {} must be of shape ({}{}), one row a clump", what, n,
                             width == 1 ? "," : fmt::format(", {}", width))
               : fmt::format("add_clumps: {} must be of shape (n, {})", what, width));
  n = a.shape(0);
  return {a.data(), a.data() + a.size()};
}

// The scene's shape of that name; ValueError naming `call` and the scene's shapes where none is.
std::vector<ClumpShape>::const_iterator named_shape(const Scene& scene, const std::string& name,
                                                    const char* call) {
  const auto named = std::find_if(scene.shapes.begin(), scene.shapes.end(),
                                  [&](const ClumpShape& c) { return c.name == name; });
  if (named != scene.shapes.end()) return named;
  std::vector<std::string> names;
  for (const ClumpShape& c : scene.shapes) names.push_back(c.name);
  throw py::value_error(
      names.empty()
          ? fmt::format("{}: no shape '{}': the scene has no [[shape]]", call, name)
          : fmt::format("{}: no shape '{}' (the scene's: {})", call, name, fmt::join(names, ", ")));
}

} // namespace

py::dict shape_dict(const Scene& scene, const std::string& name) {
  const ClumpShape& shape = *named_shape(scene, name, "shape");
  std::vector<double> centres, radii;
  for (const SphereMember& m : shape.members) {
    centres.insert(centres.end(), {m.centre.x, m.centre.y, m.centre.z});
    radii.push_back(m.radius);
  }
  const auto k = static_cast<py::ssize_t>(radii.size());
  const Vec3& i = shape.inertia_per_density;
  const Quaternion& f = shape.frame;
  return py::dict("centres"_a = rows_of(centres, k, 3), "radii"_a = rows_of(radii, k, 1),
                  "volume"_a = shape.volume,
                  "inertia_per_density"_a = rows_of(std::vector<double>{i.x, i.y, i.z}, 3, 1),
                  "bounding_radius"_a = shape.bounding_radius,
                  "frame"_a = rows_of(std::vector<double>{f.w, f.x, f.y, f.z}, 4, 1),
                  "centre"_a = rows_of(
                      std::vector<double>{shape.centre.x, shape.centre.y, shape.centre.z}, 3, 1));
}

std::vector<Quaternion> unit_quaternions(std::span<const double> rows, const char* call) {
  std::vector<Quaternion> out;
  for (std::size_t k = 0; 4 * k + 3 < rows.size(); ++k) {
    const Quaternion o{rows[4 * k], rows[4 * k + 1], rows[4 * k + 2], rows[4 * k + 3]};
    const double norm_q = std::sqrt(dot(o, o));
    if (!(std::abs(norm_q - 1.0) <= 1e-6))
      throw py::value_error(
          fmt::format("{}: orientations[{}] = ({}, {}, {}, {}) has norm {:.9g}: give a unit "
                      "quaternion (w, x, y, z), such as (1, 0, 0, 0)",
                      call, k, o.w, o.x, o.y, o.z, norm_q));
    out.push_back((1.0 / norm_q) * o);
  }
  return out;
}

std::vector<PlacedClump> placed_clumps(const Scene& scene, const std::string& shape,
                                       const DoubleRows& x, const DoubleRows& q,
                                       const DoubleRows& v, const DoubleRows& w,
                                       const DoubleRows& scale, const std::string& material,
                                       bool principal) {
  const auto named = named_shape(scene, shape, "add_clumps");
  const auto kind = scene.material_index(material);
  if (!kind) throw py::value_error(fmt::format("add_clumps: no material '{}'", material));
  const double density = scene.material_properties[*kind].density;
  if (!(density > 0))
    throw py::value_error(fmt::format("add_clumps: material '{}' has no density", material));
  py::ssize_t n = -1;
  const std::vector<double> at = rows(x, 3, n, "positions"), turn = rows(q, 4, n, "orientations"),
                            vel = rows(v, 3, n, "velocities"),
                            spin = rows(w, 3, n, "angular_velocities"),
                            factor = rows(scale, 1, n, "scale");
  std::vector<PlacedClump> out;
  const auto row3 = [](const std::vector<double>& c, std::size_t k) {
    return Vec3{c[3 * k], c[3 * k + 1], c[3 * k + 2]};
  };
  const std::vector<Quaternion> unit = unit_quaternions(turn, "add_clumps");
  for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) {
    const Quaternion& o = unit[k];
    if (!(factor[k] > 0) || !std::isfinite(factor[k]))
      throw py::value_error(
          fmt::format("add_clumps: scale[{}] = {} is not positive and finite", k, factor[k]));
    try {
      out.push_back(make_clump(named->scaled(factor[k]), density, *kind, 0, row3(at, k),
                               principal ? o : o * named->frame, row3(vel, k), row3(spin, k)));
    } catch (const std::invalid_argument& e) {
      throw py::value_error(fmt::format("add_clumps: clump {}: {}", k, e.what()));
    }
    out.back().body.shape = static_cast<std::int32_t>(named - scene.shapes.begin());
  }
  return out;
}

} // namespace yuxi::python
