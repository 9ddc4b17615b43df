#include "py_coarse_grain.hpp"

#include "analysis/cg_cylinder.hpp"
#include "analysis/coarse_grain.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <functional>
#include <optional>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <stdexcept>
#include <string>
#include <vector>

namespace py = pybind11;
using namespace pybind11::literals;

namespace yuxi::python {
namespace {

using analysis::CgContact;
using analysis::CgFields;
using analysis::CgKind;
using analysis::CgSettings;

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The rows of a (n, 3) array as Vec3s; `name` in the error.
std::vector<Vec3> vectors(const Doubles& a, py::ssize_t n, const std::string& name) {
  if (a.ndim() != 2 || a.shape(1) != 3 || a.shape(0) != n)
    throw std::invalid_argument("coarse_grain: " + name + " must have shape (" + std::to_string(n) +
                                ", 3)");
  std::vector<Vec3> out(static_cast<std::size_t>(n));
  const double* d = a.data();
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = {d[3 * k], d[3 * k + 1], d[3 * k + 2]};
  return out;
}
std::vector<double> scalars(const Doubles& a, py::ssize_t n, const std::string& name) {
  if (a.ndim() != 1 || a.shape(0) != n)
    throw std::invalid_argument("coarse_grain: " + name + " must have shape (" + std::to_string(n) +
                                ",)");
  return {a.data(), a.data() + n};
}

CgKind kind_named(const std::string& name) {
  for (const CgKind k : {CgKind::gaussian, CgKind::lucy, CgKind::bins})
    if (analysis::to_string(k) == name) return k;
  throw std::invalid_argument("coarse_grain: function must be \"gaussian\", \"lucy\" or "
                              "\"bins\" (got \"" +
                              name + "\")");
}

// An axis set such as "xy": which of x, y, z it names.
std::array<bool, 3> axes_named(const std::string& text, const std::string& key) {
  std::array<bool, 3> on{false, false, false};
  for (const char c : text) {
    if (c < 'x' || c > 'z')
      throw std::invalid_argument("coarse_grain: " + key + " names axes among x, y, z (got \"" +
                                  text + "\")");
    on[static_cast<std::size_t>(c - 'x')] = true;
  }
  return on;
}

// A field of the grid as an array indexed [i, j, k] over the resolved axes, then its components.
// (n: the points along the grid's three axes, first fastest; averaged: the axes left out.)
py::array_t<double> field(const std::vector<double>& values, const std::array<int, 3>& n,
                          const std::array<bool, 3>& averaged, int components) {
  std::vector<py::ssize_t> shape, strides;
  const auto c = static_cast<py::ssize_t>(components);
  const py::ssize_t stride[3] = {c * 8, c * 8 * n[0], c * 8 * n[0] * n[1]};
  for (int a = 0; a < 3; ++a)
    if (!averaged[static_cast<std::size_t>(a)]) {
      shape.push_back(n[static_cast<std::size_t>(a)]);
      strides.push_back(stride[a]);
    }
  if (components == 3) shape.push_back(3), strides.push_back(8);
  if (components == 9) {
    shape.insert(shape.end(), {3, 3});
    strides.insert(strides.end(), {24, 8});
  }
  py::array_t<double> strided(shape, strides, values.data());
  return py::array_t<double>(strided.attr("copy")());
}

// Contacts as analysis::CgContact's fields (yuxi/coarse_graining.py makes them); none for None.
std::vector<CgContact> contact_list(const py::object& contacts) {
  std::vector<CgContact> list;
  if (!contacts.is_none()) {
    const py::dict d = contacts.cast<py::dict>();
    for (const char* key :
         {"centre", "volume", "wall", "volume_b", "force", "branch", "point", "elastic"})
      if (!d.contains(key))
        throw std::invalid_argument(std::string("coarse_grain: contacts need the key '") + key +
                                    "'");
    const Doubles volume_a = d["volume"].cast<Doubles>();
    const py::ssize_t count = volume_a.ndim() == 1 ? volume_a.shape(0) : -1;
    if (count < 0) throw std::invalid_argument("coarse_grain: contacts' volume must be 1-D");
    const std::vector<Vec3> centre =
                                vectors(d["centre"].cast<Doubles>(), count, "contacts' centre"),
                            force = vectors(d["force"].cast<Doubles>(), count, "contacts' force"),
                            branch =
                                vectors(d["branch"].cast<Doubles>(), count, "contacts' branch"),
                            point = vectors(d["point"].cast<Doubles>(), count, "contacts' point");
    const std::vector<double> va = scalars(volume_a, count, "contacts' volume"),
                              vb = scalars(d["volume_b"].cast<Doubles>(), count,
                                           "contacts' volume_b"),
                              elastic =
                                  scalars(d["elastic"].cast<Doubles>(), count, "contacts' elastic"),
                              wall = scalars(d["wall"].cast<Doubles>(), count, "contacts' wall");
    // Optional: the power each dissipates (W), the energy in its relaxation buffer (J) and the
    // power of a moving wall on its grain (W).
    const auto optional = [&](const char* key, const std::string& name) {
      return d.contains(key) ? scalars(d[key].cast<Doubles>(), count, name)
                             : std::vector<double>(static_cast<std::size_t>(count), 0.0);
    };
    const std::vector<double> dissipation = optional("dissipation", "contacts' dissipation"),
                              relaxation = optional("relaxation", "contacts' relaxation"),
                              wall_power = optional("wall_power", "contacts' wall_power");
    for (std::size_t k = 0; k < static_cast<std::size_t>(count); ++k)
      list.push_back({centre[k], va[k], wall[k] != 0.0, vb[k], force[k], branch[k], point[k],
                      elastic[k], -1, -1, dissipation[k], relaxation[k], wall_power[k]});
  }
  return list;
}

// The sums of this rank, added over the ranks where `reduce` is given (it sums a numpy array over
// the ranks, in place): every rank then makes the fields of the whole.
void reduce_sums(std::vector<double>& sums, const py::object& reduce) {
  if (!reduce.is_none())
    reduce(py::array_t<double>(static_cast<py::ssize_t>(sums.size()), sums.data(),
                               py::capsule(sums.data(), [](void*) {})));
}

// What both grids take: the grains, the contacts and the function.
struct Input {
  std::vector<Vec3> x, v;
  std::vector<double> mass, volume;
  std::vector<CgContact> contacts;
  CgKind kind = CgKind::gaussian;
  double width = 0.0, cutoff = 0.0;
  analysis::CgGrains grains() const { return {x, v, mass, volume}; }
};

Input input_of(const Doubles& x, const Doubles& v, const Doubles& mass, const Doubles& volume,
               const py::object& contacts, const std::string& function, double width,
               std::optional<double> cutoff) {
  const py::ssize_t grains = x.ndim() == 2 ? x.shape(0) : -1;
  if (grains < 0) throw std::invalid_argument("coarse_grain: x must have shape (n, 3)");
  Input in{vectors(x, grains, "x"),
           vectors(v, grains, "v"),
           scalars(mass, grains, "mass"),
           scalars(volume, grains, "volume"),
           contact_list(contacts),
           kind_named(function),
           width,
           cutoff.value_or(3.0 * width)};
  if (in.kind != CgKind::bins && !(width > 0.0))
    throw std::invalid_argument("coarse_grain: width must be positive (got " +
                                std::to_string(width) + ")");
  return in;
}

// The coordinates of the points along an axis, as an array.
py::array_t<double> coordinates(int n, const std::function<double(int)>& at) {
  std::vector<double> values(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) values[static_cast<std::size_t>(k)] = at(k);
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

py::dict coarse_grain(const Doubles& x, const Doubles& v, const Doubles& mass,
                      const Doubles& volume, const py::object& contacts,
                      const std::string& function, double width, std::optional<double> cutoff,
                      const Doubles& lo, const Doubles& hi, const std::vector<int>& n,
                      const std::string& average, const std::string& periodic,
                      const py::object& reduce) {
  const Input in = input_of(x, v, mass, volume, contacts, function, width, cutoff);
  CgSettings settings;
  settings.kind = in.kind;
  settings.width = in.width;
  settings.cutoff = in.cutoff;
  if (lo.size() != 3 || hi.size() != 3 || n.size() != 3)
    throw std::invalid_argument("coarse_grain: lo, hi and n take three values (x, y, z)");
  settings.grid.lo = {lo.data()[0], lo.data()[1], lo.data()[2]};
  settings.grid.hi = {hi.data()[0], hi.data()[1], hi.data()[2]};
  settings.grid.averaged = axes_named(average, "average");
  settings.grid.periodic = axes_named(periodic, "periodic");
  for (std::size_t a = 0; a < 3; ++a) settings.grid.n[a] = settings.grid.averaged[a] ? 1 : n[a];

  std::vector<double> sums;
  {
    py::gil_scoped_release release;
    sums = analysis::coarse_grain_sums(in.grains(), in.contacts, settings);
  }
  reduce_sums(sums, reduce);
  const CgFields f = analysis::coarse_grain_fields(sums, settings.grid);
  const analysis::CgGrid& grid = settings.grid;
  py::dict out;
  static constexpr const char* axis_names[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a)
    if (!grid.averaged[static_cast<std::size_t>(a)])
      out[axis_names[a]] = coordinates(grid.n[static_cast<std::size_t>(a)],
                                       [&](int k) { return grid.coordinate(a, k); });
  for (const analysis::CgNamedField& named : analysis::named_fields(f))
    out[py::str(std::string(named.name))] =
        field(*named.values, grid.n, grid.averaged, named.components);
  out["cell_volume"] = grid.cell_volume();
  return out;
}

// On a cylindrical grid (analysis/cg_cylinder.hpp): the axis (x0, y0), lo = (r_lo, z_lo), hi =
// (r_hi, z_hi), n = (n_r, n_theta, n_z); average names "theta", "z" or both.
py::dict coarse_grain_cylinder(const Doubles& x, const Doubles& v, const Doubles& mass,
                               const Doubles& volume, const py::object& contacts,
                               const std::string& function, double width,
                               std::optional<double> cutoff, const Doubles& axis, const Doubles& lo,
                               const Doubles& hi, const std::vector<int>& n,
                               const std::string& average, const py::object& reduce) {
  const Input in = input_of(x, v, mass, volume, contacts, function, width, cutoff);
  analysis::CgCylinderSettings settings;
  settings.kind = in.kind;
  settings.width = in.width;
  settings.cutoff = in.cutoff;
  if (axis.size() != 2 || lo.size() != 2 || hi.size() != 2 || n.size() != 3)
    throw std::invalid_argument("coarse_grain: on a cylindrical grid, axis takes (x, y), lo and "
                                "hi take (r, z), n takes (n_r, n_theta, n_z)");
  std::string rest = average;
  const auto take = [&rest](const std::string& word) {
    const auto at = rest.find(word);
    if (at == std::string::npos) return false;
    rest.erase(at, word.size());
    return true;
  };
  const bool theta_averaged = take("theta"), z_averaged = take("z");
  if (rest.find_first_not_of(" ,") != std::string::npos)
    throw std::invalid_argument("coarse_grain: on a cylindrical grid, average names \"theta\", "
                                "\"z\" or both (got \"" +
                                average + "\")");
  settings.grid = {axis.data()[0],
                   axis.data()[1],
                   lo.data()[0],
                   hi.data()[0],
                   lo.data()[1],
                   hi.data()[1],
                   {n[0], theta_averaged ? 1 : n[1], z_averaged ? 1 : n[2]},
                   theta_averaged,
                   z_averaged};
  std::vector<double> sums;
  {
    py::gil_scoped_release release;
    sums = analysis::coarse_grain_sums(in.grains(), in.contacts, settings);
  }
  reduce_sums(sums, reduce);
  const CgFields f = analysis::coarse_grain_fields(sums, settings.grid.size());
  const analysis::CgCylinder& g = settings.grid;
  py::dict out;
  out["r"] = coordinates(g.n[0], [&](int k) { return g.r(k); });
  if (!theta_averaged) out["theta"] = coordinates(g.n[1], [&](int k) { return g.theta(k); });
  if (!z_averaged) out["z"] = coordinates(g.n[2], [&](int k) { return g.z(k); });
  const std::array<bool, 3> averaged{false, theta_averaged, z_averaged};
  for (const analysis::CgNamedField& named : analysis::named_fields(f))
    out[py::str(std::string(named.name))] = field(*named.values, g.n, averaged, named.components);
  out["cell_volume"] = coordinates(g.n[0], [&](int k) { return g.cell_volume(k); });
  return out;
}

} // namespace

void bind_coarse_grain(py::module_& m) {
  m.def("coarse_grain", &coarse_grain, "x"_a, "v"_a, "mass"_a, "volume"_a, "contacts"_a,
        "function"_a, "width"_a, "cutoff"_a, "lo"_a, "hi"_a, "n"_a, "average"_a, "periodic"_a,
        "reduce"_a = py::none());
  m.def("coarse_grain_cylinder", &coarse_grain_cylinder, "x"_a, "v"_a, "mass"_a, "volume"_a,
        "contacts"_a, "function"_a, "width"_a, "cutoff"_a, "axis"_a, "lo"_a, "hi"_a, "n"_a,
        "average"_a, "reduce"_a = py::none());
}

} // namespace yuxi::python
