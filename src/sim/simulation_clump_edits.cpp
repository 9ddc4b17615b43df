// Changes to a simulation's clumps between steps from outside the equations of motion (the
// Python API): a clump's velocity and angular velocity set, clumps added at a chosen pose and
// removed whole. Each change books the mechanical energy it makes or takes, as the grains' edits
// do (simulation_edits.cpp; docs/ARCHITECTURE.md, "Energy books").
#include "contact/contact_history.hpp"
#include "scene/clump_shape.hpp"
#include "sim/cell_sizing.hpp"
#include "sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace yuxi {

std::vector<std::size_t> Simulation::clump_indices(std::span<const GlobalId> ids,
                                                   bool others_passed) const {
  std::vector<std::size_t> out;
  out.reserve(ids.size());
  const OwnedIndex index(store_);
  for (const GlobalId id : ids) {
    if (const std::size_t b = clumps_.find(id); b < clumps_.size()) {
      out.push_back(b);
      continue;
    }
    // (a particle here, but no clump's id: say what it is)
    if (const std::size_t i = index.find(id); i != OwnedIndex::none) {
      if (!store_.is_grain(i))
        throw std::invalid_argument(
            fmt::format("id {} is a wall particle's, not a clump's: a clump is named by the id "
                        "of its member 0 (sim.clumps()[\"id\"])",
                        id));
      if (store_.body[i] < 0)
        throw std::invalid_argument(fmt::format(
            "id {} is a free grain's, not a clump's: a clump is named by the id of its member 0 "
            "(sim.clumps()[\"id\"])",
            id));
      throw std::invalid_argument(
          fmt::format("id {} is member {} of clump {}: a clump is named by the id of its member "
                      "0, {}",
                      id, id - store_.body[i], store_.body[i], store_.body[i]));
    }
    if (!others_passed)
      throw std::invalid_argument(
          fmt::format("clump id {} is not one of this rank's clumps (rank {} owns {})", id,
                      comm().rank(), clumps_.size()));
  }
  return out;
}

namespace {

void check_values(std::span<const GlobalId> ids, std::span<const Vec3> values, const char* what) {
  if (ids.size() != values.size())
    throw std::invalid_argument(
        fmt::format("clump {}: {} ids but {} values", what, ids.size(), values.size()));
  for (std::size_t k = 0; k < ids.size(); ++k)
    if (!is_finite(values[k]))
      throw std::invalid_argument(fmt::format("{} of clump {} is not finite", what, ids[k]));
}

} // namespace

void Simulation::set_clump_motions(std::span<const GlobalId> ids, std::span<const Vec3> values,
                                   const char* what,
                                   const std::function<void(ClumpBody&, const Vec3&)>& write) {
  check_values(ids, values, what);
  const std::vector<std::size_t> at = clump_indices(ids, false);
  ++edits_;
  const Vec3 g = potential_gravity(config_);
  for (std::size_t k = 0; k < at.size(); ++k) {
    const double before = clumps_.mechanical_energy(at[k], g);
    write(clumps_.motion_of(at[k]), values[k]);
    ledger_.books().inserted += clumps_.mechanical_energy(at[k], g) - before;
  }
  clumps_.place_members(store_, 0.0, nullptr); // (the members' velocities)
}

void Simulation::set_clump_velocities(std::span<const GlobalId> ids, std::span<const Vec3> v) {
  set_clump_motions(ids, v, "velocity", [](ClumpBody& b, const Vec3& value) { b.v = value; });
}

void Simulation::set_clump_angular_velocities(std::span<const GlobalId> ids,
                                              std::span<const Vec3> w) {
  set_clump_motions(ids, w, "angular velocity",
                    [](ClumpBody& b, const Vec3& value) { b.set_angular_velocity(value); });
}

void Simulation::set_clump_poses(std::span<const GlobalId> ids, std::span<const Vec3> x,
                                 std::span<const Quaternion> q) {
  edit_particles(
      [&] {
        // (every check in here, so that every rank throws together)
        if (ids.size() != x.size() || (!q.empty() && q.size() != ids.size()))
          throw std::invalid_argument(fmt::format("clump poses: {} ids but {} positions and {} "
                                                  "orientations",
                                                  ids.size(), x.size(), q.size()));
        const std::vector<std::size_t> at = clump_indices(ids, false); // (throws for a non-clump)
        for (std::size_t k = 0; k < ids.size(); ++k) {
          if (!is_finite(x[k]) || !config_.box.contains(config_.box.wrap(x[k])))
            throw std::invalid_argument(
                fmt::format("position ({}, {}, {}) of clump {} is outside the domain", x[k].x,
                            x[k].y, x[k].z, ids[k]));
          if (!q.empty() && !is_unit(q[k]))
            throw std::invalid_argument(
                fmt::format("orientation ({}, {}, {}, {}) of clump {} is not a unit quaternion",
                            q[k].w, q[k].x, q[k].y, q[k].z, ids[k]));
          // Every member inside the domain, where the pose puts it.
          const ClumpBody& body = clumps_.bodies()[at[k]];
          const Quaternion turn = q.empty() ? body.q : q[k];
          for (std::size_t m = 0; m < body.members.size(); ++m) {
            const Vec3 member = x[k] + to_lab(turn, body.members[m]);
            if (!config_.box.contains(config_.box.wrap(member)))
              throw std::invalid_argument(fmt::format(
                  "member {} of clump {} would stand at ({:.6g}, {:.6g}, {:.6g}), outside the "
                  "domain",
                  m, ids[k], member.x, member.y, member.z));
          }
        }
      },
      [&] {
        // (found again: the list build may have taken escaped clumps out before this)
        const std::vector<std::size_t> at = clump_indices(ids, true);
        for (std::size_t k = 0, b = 0; k < ids.size(); ++k) {
          if (b == at.size() || clumps_.bodies()[at[b]].id != ids[k]) continue;
          ClumpBody& body = clumps_.motion_of(at[b++]);
          body.x = x[k];
          if (q.empty()) continue;
          const Vec3 omega = body.angular_velocity();
          body.q = q[k];
          body.set_angular_velocity(omega);
        }
        clumps_.index_members(store_); // (escapes may have moved the members since)
        double moved2 = 0.0;
        clumps_.place_members(store_, 0.0, &moved2);
      });
}

std::vector<GlobalId> Simulation::add_clumps(std::vector<PlacedClump> clumps) {
  std::vector<GlobalId> ids;
  std::vector<ParticleSpec> members; // every new member, clump by clump
  std::vector<std::size_t> clump_of;
  double reach = 0.0;
  GlobalId next = sources_.next_id();
  for (std::size_t c = 0; c < clumps.size(); ++c) {
    const ClumpBody& body = clumps[c].body;
    const auto where = [&] { return fmt::format("new clump {}", c); };
    if (!is_finite(body.x) || !config_.box.contains(body.x))
      throw std::invalid_argument(where() + ": its centre of mass is outside the domain");
    if (!is_finite(body.v) || !is_finite(body.angular_velocity()))
      throw std::invalid_argument(where() + ": its velocities must be finite");
    if (body.material >= contacts_.n_materials())
      throw std::invalid_argument(fmt::format("{}: material {} is not one of the scene's {}",
                                              where(), body.material, contacts_.n_materials()));
    for (std::size_t k = 0; k < clumps[c].members.size(); ++k) {
      const ParticleSpec& m = clumps[c].members[k];
      if (!is_finite(m.position) || !config_.box.contains(config_.box.wrap(m.position)))
        throw std::invalid_argument(
            fmt::format("{}: member {} at ({:.6g}, {:.6g}, {:.6g}) is outside the domain", where(),
                        k, m.position.x, m.position.y, m.position.z));
      members.push_back(m);
      clump_of.push_back(c);
    }
    // (the largest member, so that the advice makes room for every one)
    const auto largest = std::max_element(
        clumps[c].members.begin(), clumps[c].members.end(),
        [](const ParticleSpec& a, const ParticleSpec& b) { return a.radius < b.radius; });
    if (largest != clumps[c].members.end())
      if (const std::string why =
              cells_too_small_for(largest->radius, exchange_.cell_edge(), config_.skin);
          !why.empty())
        throw std::invalid_argument(
            fmt::format("{}: member {}: {}", where(), largest - clumps[c].members.begin(), why));
    check_clump_span(body.span(), where());
    reach = std::max(reach, clump_reach(body.members));
    ids.push_back(next);
    next += static_cast<GlobalId>(clumps[c].members.size());
  }
  // A clump's members stand up to `reach` outside the sub-domain of its owner: the ghosts reach
  // as far from this list build on (the same list on every rank: the same reach), which every
  // sub-domain crossed by ghosts must be wide enough for; where the edit fails, the reach is
  // put back.
  const double old_reach = exchange_.clump_reach();
  const bool wider = ghosts_reach_for_clumps() && reach > old_reach;
  if (wider) {
    const Decomposition& d = exchange_.decomposition();
    for (int a = 0; a < 3; ++a)
      if ((d.dims()[a] > 1 || config_.box.periodic(a)) &&
          d.min_width(a) < exchange_.cell_edge() + reach)
        throw std::invalid_argument(fmt::format(
            "the new clumps' members stand up to {:.4g} from their anchor members, and a "
            "sub-domain along axis {} ({:.4g} wide) is narrower than the cells' edge plus that "
            "({:.4g}): use fewer ranks along that axis",
            reach, a, d.min_width(a), exchange_.cell_edge() + reach));
    exchange_.set_clump_reach(reach);
  }
  try {
    add_clumps_in_edit(clumps, members, clump_of);
  } catch (...) {
    if (wider) exchange_.set_clump_reach(old_reach);
    throw;
  }
  return ids;
}

void Simulation::add_clumps_in_edit(std::vector<PlacedClump>& clumps,
                                    std::span<const ParticleSpec> members,
                                    std::span<const std::size_t> clump_of) {
  // (edit_particles books their energy with the change of the contacts')
  edit_particles(
      [&] {
        for (std::size_t c = 0; c < clumps.size(); ++c)
          check_pairs_for(clumps[c].body.material, fmt::format("new clump {}", c));
        check_clear_of_particles(members, clump_of);
      },
      [&] {
        const Vec3 g = config_.gravity;
        for (PlacedClump& c : clumps) {
          ClumpBody& body = c.body;
          body.id = sources_.next_id();
          for (std::size_t k = 0; k < c.members.size(); ++k) sources_.take_id();
          // (its owner: the rank of its anchor member, sim/exchange.hpp)
          if (!exchange_.decomposition().owns(config_.box.wrap(c.members[body.anchor()].position)))
            continue;
          for (std::size_t k = 0; k < c.members.size(); ++k) {
            ParticleSpec m = c.members[k];
            m.kind = Kind::grain;
            m.body = body.id;
            store_.add(m, body.id + static_cast<GlobalId>(k));
          }
          body.force = body.mass * g;
          clumps_.add(std::move(body));
        }
      });
}

std::int64_t Simulation::remove_clumps(std::span<const GlobalId> ids) {
  std::int64_t removed = 0;
  edit_particles([&] { clump_indices(ids, true); },
                 [&] {
                   // (found again: the list build may have taken escaped clumps out before this)
                   std::vector<std::size_t> gone = clump_indices(ids, true);
                   std::sort(gone.begin(), gone.end());
                   gone.erase(std::unique(gone.begin(), gone.end()), gone.end());
                   const Vec3 g = potential_gravity(config_);
                   for (const std::size_t b : gone)
                     ledger_.books().removed += clumps_.mechanical_energy(b, g);
                   removed = static_cast<std::int64_t>(gone.size());
                   if (gone.empty()) return;
                   const std::vector<std::size_t> members = clumps_.remove(store_, gone);
                   store_.remove_owned(members);
                 });
  // (the ghosts' reach of the clumps left, as a run resumed from here computes it)
  update_clump_reach();
  return comm().sum(removed);
}

} // namespace yuxi
