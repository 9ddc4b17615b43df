// Changes to a simulation's state between steps from outside the equations of motion: the
// Python API's writes to velocities and positions, grains added and removed by a script, and
// inserts added. Each change books the mechanical energy it makes or takes
// (docs/ARCHITECTURE.md, "Energy books"), so the books keep closing.
#include "contact/contact_history.hpp"
#include "scene/ball_hash.hpp"
#include "scene/closest_point_on_triangle.hpp"
#include "sim/cell_sizing.hpp"
#include "sim/simulation.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <variant>

namespace yuxi {

std::vector<std::size_t> Simulation::grain_indices(std::span<const GlobalId> ids) const {
  const OwnedIndex index(store_);
  std::vector<std::size_t> out;
  out.reserve(ids.size());
  for (const GlobalId id : ids) {
    const std::size_t i = index.find(id);
    if (i == OwnedIndex::none)
      throw std::invalid_argument(
          fmt::format("particle id {} is not one of this rank's particles (rank {} owns {})", id,
                      comm().rank(), store_.n_owned()));
    if (!store_.is_grain(i))
      throw std::invalid_argument(fmt::format(
          "particle id {} is a wall particle: its motion is the scene's, not set from outside",
          id));
    if (store_.body[i] >= 0)
      throw std::invalid_argument(
          fmt::format("particle id {} is a member of clump {}: it moves with its clump, not "
                      "alone (set the clump's motion, by its id {})",
                      id, store_.body[i], store_.body[i]));
    out.push_back(i);
  }
  return out;
}

namespace {

void check_sizes(std::size_t ids, std::size_t values, const char* what) {
  if (ids != values)
    throw std::invalid_argument(fmt::format("{}: {} ids but {} values", what, ids, values));
}

} // namespace

void Simulation::set_velocities(std::span<const GlobalId> ids, std::span<const Vec3> v) {
  check_sizes(ids.size(), v.size(), "velocities");
  const std::vector<std::size_t> at = grain_indices(ids);
  for (std::size_t k = 0; k < ids.size(); ++k)
    if (!is_finite(v[k]))
      throw std::invalid_argument(fmt::format("velocity of particle id {} is not finite", ids[k]));
  ++edits_;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const std::size_t i = at[k];
    ledger_.books().inserted += 0.5 * store_.mass[i] * (norm2(v[k]) - norm2(store_.v[i]));
    store_.v[i] = v[k];
  }
}

void Simulation::set_angular_velocities(std::span<const GlobalId> ids, std::span<const Vec3> w) {
  check_sizes(ids.size(), w.size(), "angular velocities");
  const std::vector<std::size_t> at = grain_indices(ids);
  for (std::size_t k = 0; k < ids.size(); ++k)
    if (!is_finite(w[k]))
      throw std::invalid_argument(
          fmt::format("angular velocity of particle id {} is not finite", ids[k]));
  ++edits_;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const std::size_t i = at[k];
    const double before = rotational_energy(i);
    store_.w[i] = w[k];
    ledger_.books().inserted += rotational_energy(i) - before;
  }
}

void Simulation::edit_particles(const std::function<void()>& check,
                                const std::function<void()>& change) {
  // Every rank checks its part first, so that none is left waiting in the list build.
  std::string error;
  try {
    check();
  } catch (const std::invalid_argument& e) {
    error = e.what();
  }
  error = comm().first_error(error);
  if (!error.empty()) throw std::invalid_argument(error);
  ++edits_;
  const EnergyBooks before = energies(); // collective
  // (the change is made in the list build, once the history is stashed)
  build_lists({ListBuildPlan::After::edit, &change});
  start_forces_from_gravity();
  compute_forces(false);
  stop_if_unhealthy();
  // What came in: the change of mechanical energy, and what the removed grains took away.
  const EnergyBooks after = energies();
  if (comm().root())
    ledger_.books().inserted += (after.mechanical() + after.relaxation) -
                                (before.mechanical() + before.relaxation) +
                                (after.removed - before.removed);
}

void Simulation::set_positions(std::span<const GlobalId> ids, std::span<const Vec3> x) {
  check_sizes(ids.size(), x.size(), "positions");
  edit_particles(
      [&] {
        grain_indices(ids); // (throws for an id that is not one)
        for (std::size_t k = 0; k < ids.size(); ++k)
          if (!is_finite(x[k]) || !config_.box.contains(config_.box.wrap(x[k])))
            throw std::invalid_argument(
                fmt::format("position ({}, {}, {}) of particle id {} is outside the domain", x[k].x,
                            x[k].y, x[k].z, ids[k]));
      },
      [&] {
        // (found again: the list build may have taken escaped grains out before this)
        const OwnedIndex index(store_);
        for (std::size_t k = 0; k < ids.size(); ++k)
          if (const std::size_t i = index.find(ids[k]); i != OwnedIndex::none) store_.x[i] = x[k];
      });
}

void Simulation::check_pairs_for(std::uint8_t material, const std::string& who) const {
  // The materials this grain can meet: this rank's particles' (every rank checks its own), the
  // planes' and the shaped walls'.
  const std::size_t n_materials = contacts_.n_materials();
  std::vector<bool> present(n_materials, false);
  for (std::size_t i = 0; i < store_.n_owned(); ++i)
    if (store_.material[i] < n_materials) present[store_.material[i]] = true;
  walls_.mark_materials(present);
  present[material] = true; // (with the grains like it)
  for (std::size_t m = 0; m < n_materials; ++m)
    if (present[m] && !contacts_.has_pair(material, static_cast<std::uint8_t>(m)))
      throw std::invalid_argument(
          fmt::format("{}: the scene has no contact pair for materials {} and {}, which can touch",
                      who, material, m));
}

void Simulation::check_clear_of_particles(std::span<const ParticleSpec> grains,
                                          std::span<const std::size_t> clump_of) const {
  // This rank's particles and the new grains before each, hashed on cells as wide as the
  // widest contact; along a periodic axis a grain near a face is looked for at its image too.
  // A touch within 1e-9 of the radius (grains placed exactly in contact) is no overlap. A new
  // clump's members join the hash once the whole clump is checked (they overlap one another).
  const auto name = [&](std::size_t k) {
    if (clump_of.empty()) return fmt::format("new grain {}", k);
    std::size_t first = k;
    while (first > 0 && clump_of[first - 1] == clump_of[k]) --first;
    return fmt::format("member {} of new clump {}", k - first, clump_of[k]);
  };
  double widest = 0.0;
  for (const ParticleSpec& p : grains) widest = std::max(widest, p.radius);
  for (std::size_t i = 0; i < store_.n_owned(); ++i) widest = std::max(widest, store_.radius[i]);
  const double edge = 2.0 * widest;
  BallHash owned(edge), added(edge);
  std::vector<std::size_t> added_ids;
  for (std::size_t i = 0; i < store_.n_owned(); ++i)
    owned.add(config_.box.wrap(store_.x[i]), store_.radius[i]);
  const Box& box = config_.box;
  // The shaped walls as they stand now, those active: a cylinder is asked for its touches; a
  // mesh is taken whole (a rank holds only the triangles near its own grains), its corners
  // placed where it stands, and the triangles whose boxes meet the new grains' box listed
  // once; a grain overlaps it where one of those comes closer than its radius.
  struct PlacedWall {
    const ShapedWall* wall = nullptr;
    const TriangleMesh* mesh = nullptr; // null: a cylinder
    std::vector<Vec3> corners;
    std::vector<std::uint32_t> near;
  };
  const auto boxes_meet = [](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& lo,
                             const Vec3& hi) {
    for (int k = 0; k < 3; ++k)
      if (std::max({a[k], b[k], c[k]}) < lo[k] || std::min({a[k], b[k], c[k]}) > hi[k])
        return false;
    return true;
  };
  std::vector<PlacedWall> shaped;
  if (!grains.empty()) {
    Vec3 low = box.wrap(grains[0].position), high = low;
    for (const ParticleSpec& p : grains) {
      const Vec3 x = box.wrap(p.position);
      for (int a = 0; a < 3; ++a)
        low[a] = std::min(low[a], x[a]), high[a] = std::max(high[a], x[a]);
    }
    const Vec3 reach{widest, widest, widest};
    for (const ShapedWall& wall : walls_.shaped()) {
      if (!wall_active(wall, time_)) continue;
      PlacedWall& placed = shaped.emplace_back();
      placed.wall = &wall;
      if (const auto* mesh = std::get_if<MeshWall>(&wall)) {
        placed.mesh = &mesh->whole_mesh();
        placed.corners = mesh->placed_whole();
        for (std::size_t t = 0; t < placed.mesh->triangles.size(); ++t) {
          const auto& tri = placed.mesh->triangles[t];
          if (boxes_meet(placed.corners[tri[0]], placed.corners[tri[1]], placed.corners[tri[2]],
                         low - reach, high + reach))
            placed.near.push_back(static_cast<std::uint32_t>(t));
        }
      }
    }
  }
  std::size_t waiting = 0; // the first grain not yet in `added`
  for (std::size_t k = 0; k < grains.size(); ++k) {
    const bool same_clump = !clump_of.empty() && waiting < k && clump_of[waiting] == clump_of[k];
    for (; !same_clump && waiting < k; ++waiting) {
      added.add(box.wrap(grains[waiting].position), grains[waiting].radius);
      added_ids.push_back(waiting);
    }
    const Vec3 x = box.wrap(grains[k].position);
    const double r = grains[k].radius * (1.0 - 1e-9);
    std::vector<Vec3> images{x};
    for (int a = 0; a < 3; ++a) {
      if (!box.periodic(a)) continue;
      Vec3 shift;
      shift[a] = x[a] - box.lo[a] < edge ? box.length(a)
                                         : (box.hi[a] - x[a] < edge ? -box.length(a) : 0.0);
      if (shift[a] == 0.0) continue;
      const std::size_t n = images.size();
      for (std::size_t m = 0; m < n; ++m) images.push_back(images[m] + shift);
    }
    const auto refuse = [&](const std::string& what, double overlap) {
      throw std::invalid_argument(fmt::format(
          "{} at ({:.6g}, {:.6g}, {:.6g}), radius {:.4g}, overlaps {} by {:.4g} ({:.3g} % of its "
          "radius): grains are added clear of every particle and wall (move it, or remove what "
          "is there first)",
          name(k), x.x, x.y, x.z, grains[k].radius, what, overlap,
          100.0 * overlap / grains[k].radius));
    };
    for (const Vec3& at : images) {
      if (const std::size_t b = owned.first_overlapping(at, r); b != BallHash::none)
        refuse(!store_.is_grain(b)   ? fmt::format("wall particle {}", store_.gid[b])
               : store_.body[b] >= 0 ? fmt::format("member {} of clump {}",
                                                   store_.gid[b] - store_.body[b], store_.body[b])
                                     : fmt::format("grain {}", store_.gid[b]),
               grains[k].radius + owned.radius(b) - norm(owned.position(b) - at));
      if (const std::size_t b = added.first_overlapping(at, r); b != BallHash::none)
        refuse(fmt::format("{} of the same call", name(added_ids[b])),
               grains[k].radius + added.radius(b) - norm(added.position(b) - at));
    }
    for (const PlaneWall& w : walls_.planes())
      if (const double d = w.distance(x, time_); d < r)
        refuse(fmt::format("the flat wall '{}'", w.name), grains[k].radius - d);
    for (const PlacedWall& placed : shaped) {
      const auto what = [&] {
        return fmt::format("the {} '{}'", placed.mesh ? "mesh" : "cylinder",
                           wall_name(*placed.wall));
      };
      if (!placed.mesh) {
        WallTouches touches;
        std::get<CylinderWall>(*placed.wall).touches(x, r, touches);
        for (std::size_t c = 0; c < touches.n; ++c)
          if (touches.at[c].distance < r) refuse(what(), grains[k].radius - touches.at[c].distance);
        continue;
      }
      const Vec3 around{r, r, r};
      double nearest = r; // the closest triangle's distance, where closer than r
      for (const std::uint32_t t : placed.near) {
        const auto& tri = placed.mesh->triangles[t];
        const Vec3 &a = placed.corners[tri[0]], &b = placed.corners[tri[1]],
                   &c = placed.corners[tri[2]];
        if (boxes_meet(a, b, c, x - around, x + around))
          nearest = std::min(nearest, norm(x - closest_point_on_triangle(x, a, b, c).point));
      }
      if (nearest < r) refuse(what(), grains[k].radius - nearest);
    }
  }
}

std::vector<GlobalId> Simulation::add_grains(std::span<const ParticleSpec> grains) {
  std::vector<GlobalId> ids;
  for (std::size_t k = 0; k < grains.size(); ++k) {
    const ParticleSpec& p = grains[k];
    const auto where = [&] { return fmt::format("new grain {}", k); };
    if (!is_finite(p.position) || !config_.box.contains(p.position))
      throw std::invalid_argument(where() + ": its position is outside the domain");
    if (!(p.radius > 0) || !(p.mass > 0) || !is_finite(p.velocity) ||
        !is_finite(p.angular_velocity))
      throw std::invalid_argument(where() +
                                  ": radius and mass must be positive, velocities finite");
    if (const std::string why = cells_too_small_for(p.radius, exchange_.cell_edge(), config_.skin);
        !why.empty())
      throw std::invalid_argument(where() + ": " + why);
    if (p.material >= contacts_.n_materials())
      throw std::invalid_argument(fmt::format("{}: material {} is not one of the scene's {}",
                                              where(), p.material, contacts_.n_materials()));
    ids.push_back(sources_.next_id() + static_cast<GlobalId>(k));
  }
  // (edit_particles books their energy with the change of the contacts')
  edit_particles(
      [&] {
        for (std::size_t k = 0; k < grains.size(); ++k)
          check_pairs_for(grains[k].material, fmt::format("new grain {}", k));
        check_clear_of_particles(grains);
      },
      [&] {
        for (const ParticleSpec& spec : grains) {
          const GlobalId id = sources_.take_id();
          if (!exchange_.decomposition().owns(config_.box.wrap(spec.position))) continue;
          ParticleSpec p = spec;
          p.kind = Kind::grain;
          p.body = -1; // (a free grain; a clump is built with its body)
          p.contact_mass = 0.0;
          store_.add(p, id);
        }
      });
  return ids;
}

std::int64_t Simulation::remove_grains(std::span<const GlobalId> ids) {
  std::int64_t removed = 0;
  edit_particles(
      [&] {
        const OwnedIndex index(store_);
        for (const GlobalId id : ids)
          if (const std::size_t i = index.find(id); i != OwnedIndex::none && store_.body[i] >= 0)
            throw std::invalid_argument(fmt::format(
                "particle id {} is a member of clump {}: a clump leaves whole, not member by "
                "member (remove_clumps takes clump {})",
                id, store_.body[i], store_.body[i]));
      },
      [&] {
        const OwnedIndex index(store_);
        std::vector<std::size_t> gone;
        for (const GlobalId id : ids)
          if (const std::size_t i = index.find(id); i != OwnedIndex::none && store_.is_grain(i))
            gone.push_back(i);
        std::sort(gone.begin(), gone.end());
        gone.erase(std::unique(gone.begin(), gone.end()), gone.end());
        const Vec3 g = potential_gravity(config_);
        for (const std::size_t i : gone) ledger_.books().removed += mechanical_energy(store_, i, g);
        removed = static_cast<std::int64_t>(gone.size());
        if (!gone.empty()) store_.remove_owned(gone);
      });
  return comm().sum(removed);
}

void Simulation::add_insert(InsertSpec insert) {
  sources_.check_new_name(insert.name);
  ++edits_;
  const double cell_edge = exchange_.cell_edge();
  const double r = insert.largest_sphere();
  if (2 * r + config_.skin > cell_edge)
    throw std::invalid_argument(fmt::format(
        "insert '{}': grains of radius {} are larger than the linked cells allow ({}); the scene "
        "must pour grains that large from the start",
        insert.name, r, 0.5 * (cell_edge - config_.skin)));
  const auto k = insert.grains.material;
  if (k >= contacts_.n_materials())
    throw std::invalid_argument(fmt::format("insert '{}': material {} is not one of the scene's {}",
                                            insert.name, k, contacts_.n_materials()));
  std::string error;
  try {
    check_pairs_for(k, fmt::format("insert '{}'", insert.name));
  } catch (const std::invalid_argument& e) {
    error = e.what();
  }
  error = comm().first_error(error);
  if (!error.empty()) throw std::invalid_argument(error);
  sources_.add_insert(std::move(insert), step_, config_.dt);
  update_clump_reach(); // (from the next list build)
}

} // namespace yuxi
