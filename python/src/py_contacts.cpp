#include "py_contacts.hpp"

#include "py_rows.hpp"
#include "run/coarse_grain_contacts.hpp"

#include <cstring>
#include <numbers>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <stdexcept>
#include <utility>

namespace py = pybind11;
using namespace pybind11::literals;

namespace yuxi::python {
namespace {

// The columns of the table, filled contact by contact.
struct ContactColumns {
  std::vector<std::int64_t> id_a, id_b, element;
  std::vector<std::string> wall;
  std::vector<double> force, normal, point, overlap, elastic, state;

  void add(std::int64_t a, std::int64_t b, const std::string& wall_name, std::int64_t elem,
           const Vec3& f, const Vec3& n, const Vec3& at, double o, double e) {
    id_a.push_back(a), id_b.push_back(b), wall.push_back(wall_name), element.push_back(elem);
    append(force, f), append(normal, n), append(point, at);
    overlap.push_back(o), elastic.push_back(e);
  }
  static void append(std::vector<double>& column, const Vec3& v) {
    column.insert(column.end(), {v.x, v.y, v.z});
  }
};

} // namespace

py::dict contact_arrays(const Simulation& sim) {
  const ContactRecord& rec = sim.contact_record();
  if (!rec.enabled)
    throw std::runtime_error("contacts are not recorded: call record_contacts(True), then step");
  const ParticleStore& p = sim.particles();
  const NeighborList& list = sim.neighbor_list();
  const ContactStates& states = sim.contact_states();
  ContactColumns c;
  // Pairs: the normal points from the partner b to a; the point is the middle of the overlap.
  for (const PairContactRecord& r : rec.pairs) {
    const std::uint32_t k = r.pair, i = list.rows[k], j = list.partners[k];
    const Vec3 d = p.x[i] - p.x[j];
    const double dist = norm(d);
    const Vec3 n = d * (1.0 / dist);
    const double overlap = p.radius[i] + p.radius[j] - dist;
    c.add(p.gid[i], p.gid[j], "", -1, r.force, n, p.x[i] - n * (p.radius[i] - 0.5 * overlap),
          overlap, r.elastic);
    states.pair_state(k, c.state);
  }
  // Flat walls: the normal points from the wall to the grain; the point is on the wall.
  for (std::size_t k = 0; k < list.planes.size() && k < rec.plane_force.size(); ++k) {
    if (!rec.holds_plane(k)) continue;
    const auto& pc = list.planes[k];
    const PlaneWall& w = sim.planes()[pc.plane];
    const double dist = w.distance(p.x[pc.particle], sim.time());
    c.add(p.gid[pc.particle], -1, w.name, -1, rec.plane_force[k], w.normal,
          p.x[pc.particle] - w.normal * dist, p.radius[pc.particle] - dist, rec.plane_elastic[k]);
    states.plane_state(k, c.state);
  }
  // Meshes and cylinders: the element is the triangle or the cylinder's patch.
  for (const WallContactRecord& r : rec.wall) {
    const WallContactRef ref = list.walls[r.candidate];
    c.add(p.gid[ref.particle], -1, wall_name(sim.shaped_walls()[ref.wall]), r.element, r.force,
          r.normal, r.point, r.overlap, r.elastic);
    states.wall_state(r.candidate, r.contact, c.state);
  }

  const auto n = static_cast<py::ssize_t>(c.id_a.size());
  py::dict d;
  d["id_a"] = py::array_t<std::int64_t>(n, c.id_a.data());
  d["id_b"] = py::array_t<std::int64_t>(n, c.id_b.data());
  d["wall"] = py::module_::import("numpy").attr("array")(py::cast(c.wall), "dtype"_a = "str");
  d["element"] = py::array_t<std::int64_t>(n, c.element.data());
  d["force"] = rows_of(c.force, n, 3);
  d["normal"] = rows_of(c.normal, n, 3);
  d["point"] = rows_of(c.point, n, 3);
  d["overlap"] = rows_of(c.overlap, n, 1);
  d["elastic"] = rows_of(c.elastic, n, 1);
  // The state: each contact's values lie one after another; a field is a strided column.
  const std::vector<StateField> fields = states.state_fields();
  py::ssize_t width = 0;
  for (const StateField& f : fields) width += static_cast<py::ssize_t>(f.width);
  py::dict state;
  py::ssize_t at = 0;
  for (const StateField& f : fields) {
    const auto w = static_cast<py::ssize_t>(f.width);
    std::vector<double> column(static_cast<std::size_t>(n * w));
    for (py::ssize_t r = 0; r < n; ++r)
      for (py::ssize_t q = 0; q < w; ++q)
        column[static_cast<std::size_t>(r * w + q)] =
            c.state[static_cast<std::size_t>(r * width + at + q)];
    state[py::str(f.name)] = rows_of(column, n, w);
    at += w;
  }
  d["state"] = state;
  return d;
}

py::dict cg_contact_arrays(const Simulation& sim) {
  const std::vector<analysis::CgContact> contacts = coarse_grain_contacts(sim);
  std::vector<double> centre, volume, wall, volume_b, force, branch, point, elastic, dissipation,
      relaxation, wall_power;
  const auto vec = [](std::vector<double>& c, const Vec3& v) {
    c.insert(c.end(), {v.x, v.y, v.z});
  };
  for (const analysis::CgContact& c : contacts) {
    vec(centre, c.centre), vec(force, c.force), vec(branch, c.branch), vec(point, c.point);
    volume.push_back(c.volume), wall.push_back(c.wall ? 1.0 : 0.0);
    volume_b.push_back(c.volume_b), elastic.push_back(c.elastic);
    dissipation.push_back(c.dissipation), relaxation.push_back(c.relaxation);
    wall_power.push_back(c.wall_power);
  }
  const auto n = static_cast<py::ssize_t>(volume.size());
  py::dict d;
  d["centre"] = rows_of(centre, n, 3);
  d["volume"] = rows_of(volume, n, 1);
  d["wall"] = rows_of(wall, n, 1);
  d["volume_b"] = rows_of(volume_b, n, 1);
  d["force"] = rows_of(force, n, 3);
  d["branch"] = rows_of(branch, n, 3);
  d["point"] = rows_of(point, n, 3);
  d["elastic"] = rows_of(elastic, n, 1);
  d["dissipation"] = rows_of(dissipation, n, 1);
  d["wall_power"] = rows_of(wall_power, n, 1);
  d["relaxation"] = rows_of(relaxation, n, 1);
  return d;
}

} // namespace yuxi::python
