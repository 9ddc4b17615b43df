// The walls part: placing wall particles and shaped walls at each step, binning the meshes'
// triangles on the linked cells at a list build and listing which grains may touch which
// wall (and which of its triangles), the walls' loads and work, and their checkpoint section.
#include "sim/walls.hpp"

#include "sim/simulation_error.hpp"
#include "sim/state_layout.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <span>
#include <stdexcept>

namespace yuxi {
namespace {

// Planes standing on the faces of Boundary::wall axes, normals pointing inwards.
void add_box_walls(const SimulationConfig& c, std::vector<PlaneWall>& planes) {
  for (int a = 0; a < 3; ++a) {
    if (c.box.boundary[a] != Boundary::wall) continue;
    PlaneWall lo, hi;
    lo.point = c.box.lo;
    hi.point = c.box.hi;
    lo.normal = Vec3{};
    hi.normal = Vec3{};
    lo.normal[a] = 1.0;
    hi.normal[a] = -1.0;
    lo.material = hi.material = c.box_wall_material;
    lo.name = fmt::format("box {} lo", "xyz"[a]);
    hi.name = fmt::format("box {} hi", "xyz"[a]);
    planes.push_back(lo);
    planes.push_back(hi);
  }
}

} // namespace

Walls::Walls(const SimulationConfig& config, std::vector<PlaneWall> planes,
             std::vector<WallMotion> motions, std::vector<ShapedWall> shaped)
    : planes_(std::move(planes)), motions_(std::move(motions)), shaped_(std::move(shaped)),
      mesh_bins_(shaped_.size()), x_built_(shaped_.size()) {
  if (motions_.empty()) motions_.push_back(StaticMotion{});
  add_box_walls(config, planes_);
  work_.shaped.assign(shaped_.size(), 0.0);
  work_.planes.assign(planes_.size(), 0.0);
}

bool Walls::place(ParticleStore& s, double t, bool every_one, double* moved2) {
  const double limit2 = 0.25 * skin_ * skin_;
  bool moved_far = place_shaped(t, every_one);
  std::vector<WallMotionAtTime>& now = now_;
  std::vector<std::uint8_t>& skip = skip_; // particles of a motion at rest are already in place
  now.clear();
  skip.clear();
  particles_still_ = true;
  for (const WallMotion& m : motions_) {
    now.push_back(at_time(m, t));
    particles_still_ = particles_still_ && at_rest(now.back());
    skip.push_back(!every_one && at_rest(now.back()) ? 1 : 0);
  }
  // Motions only start (never stop), and the simulation's first placing places every wall
  // particle: while all are at rest, every wall particle stands with zero velocity, and none
  // needs placing again.
  if (particles_still_ && !every_one) return moved_far; // (frozen bases, a basin before its start)
  for (std::size_t i = 0; i < s.n_owned(); ++i) {
    if (s.is_grain(i) || skip[s.motion[i]]) continue;
    const PlacedState p = yuxi::place(now[s.motion[i]], s.x_rest[i]);
    if (moved2) *moved2 = std::max(*moved2, norm2(p.position - s.x[i]));
    s.x[i] = p.position;
    s.v[i] = p.velocity;
    if (!(norm2(p.position - s.x_build[i]) <= limit2)) moved_far = true;
  }
  return moved_far;
}

bool Walls::place_shaped(double t, bool every_one) {
  const double limit2 = 0.25 * skin_ * skin_;
  bool moved_far = false;
  for (std::size_t w = 0; w < shaped_.size(); ++w) {
    const auto& built = x_built_[w];
    if (auto* cylinder = std::get_if<CylinderWall>(&shaped_[w])) {
      if (!every_one && !cylinder->moves()) continue;
      cylinder->place(t);
      if (built.size() == 1 && !(norm2(cylinder->shift - built[0]) <= limit2)) moved_far = true;
      continue;
    }
    auto& mesh = std::get<MeshWall>(shaped_[w]);
    if (!every_one && !mesh.moves()) continue;
    mesh.place(t);
    // Its vertices; where this rank holds a part of it, the held vertices, and the bound on
    // every point's displacement (MeshWall::moved2_since_build): a triangle left out lay a cell
    // edge beyond the reach of the grains' box at the build (list_candidates), and comes within
    // it only after it has moved that much farther than half the skin.
    const auto moved_beyond = [](std::span<const Vec3> then, std::span<const Vec3> now,
                                 double most2) {
      for (std::size_t k = 0; k < then.size(); ++k)
        if (!(norm2(now[k] - then[k]) <= most2)) return true;
      return false;
    };
    if (mesh.holds_whole()) {
      if (built.size() == mesh.x.size())
        moved_far = moved_far || moved_beyond(built, mesh.x, limit2);
    } else if (built.size() == mesh.x.size()) {
      const double far = 0.5 * skin_ + cell_edge_;
      moved_far = moved_far || moved_beyond(built, mesh.x, limit2) ||
                  !(mesh.moved2_since_build() <= far * far);
    }
  }
  return moved_far;
}

void Walls::list_candidates(const ParticleStore& s, std::size_t n_grains, const CellGrid& grid,
                            double range, double t, NeighborList& list) {
  list.walls.clear();
  list.wall_elements.clear();
  if (shaped_.empty()) return;
  // The largest radius, and the box of the grains' centres (empty without grains).
  double largest = 0.0;
  constexpr double inf = std::numeric_limits<double>::infinity();
  Vec3 grains_lo{inf, inf, inf}, grains_hi{-inf, -inf, -inf};
  for (std::size_t i = 0; i < n_grains; ++i) {
    largest = std::max(largest, s.radius[i]);
    for (int a = 0; a < 3; ++a) {
      grains_lo[a] = std::min(grains_lo[a], s.x[i][a]);
      grains_hi[a] = std::max(grains_hi[a], s.x[i][a]);
    }
  }
  const double reach = largest + range;
  const Vec3 g_lo = grid.origin(), edge = grid.edge();
  const auto dims = grid.dims();
  const Vec3 g_hi{g_lo.x + dims[0] * edge.x, g_lo.y + dims[1] * edge.y, g_lo.z + dims[2] * edge.z};
  const auto grains = static_cast<std::uint32_t>(n_grains);
  for (std::uint32_t w = 0; w < shaped_.size(); ++w) {
    if (const auto* cylinder = std::get_if<CylinderWall>(&shaped_[w])) {
      if (cylinder->moves()) x_built_[w].assign(1, cylinder->shift);
      WallTouches near;
      for (std::uint32_t i = 0; i < grains; ++i) {
        cylinder->touches(s.x[i], s.radius[i] + range, near);
        if (near.n > 0) list.walls.push_back({i, w, 0, 0});
      }
      continue;
    }
    MeshWall& mesh = std::get<MeshWall>(shaped_[w]);
    MeshBins& bins = mesh_bins_[w];
    // Of a mesh, this rank holds only the triangles its grains can reach: those within the
    // reach of the grains' box grown by a cell edge. Chosen again, where the mesh stands now,
    // at every build if it moves (see place_shaped), else when the grains leave that box or
    // the reach grows.
    bool inside = bins.held_reach >= reach;
    for (int a = 0; a < 3; ++a)
      inside = inside && grains_lo[a] >= bins.held_lo[a] && grains_hi[a] <= bins.held_hi[a];
    if (mesh.moves() || !inside) {
      bins.held_reach = std::max(reach, cell_edge_ + range);
      bins.held_lo = grains_lo - Vec3{cell_edge_, cell_edge_, cell_edge_};
      bins.held_hi = grains_hi + Vec3{cell_edge_, cell_edge_, cell_edge_};
      if (mesh.hold_near(bins.held_lo, bins.held_hi, bins.held_reach)) bins.valid = false;
    }
    if (mesh.x.size() != mesh.mesh.vertices.size()) mesh.place(t);
    mesh.mark_built();
    if (mesh.moves()) x_built_[w] = mesh.x; // (a still mesh never moves from its build)
    // Each triangle's box, as placed now.
    const auto box_of = [&](std::uint32_t tri) { return mesh.mesh.box_of(tri, mesh.x); };
    if (mesh.moves() || !bins.valid || bins.reach < reach || bins.dims != dims ||
        bins.origin != g_lo) {
      // Counting sort of (cell, triangle) by cell; triangles ascend within a cell.
      std::vector<std::pair<std::uint32_t, std::uint32_t>> entries;
      for (std::uint32_t tri = 0; tri < mesh.mesh.n_triangles(); ++tri) {
        auto [lo, hi] = box_of(tri);
        bool outside = false;
        for (int a = 0; a < 3; ++a) {
          lo[a] -= reach, hi[a] += reach;
          outside = outside || hi[a] < g_lo[a] || lo[a] > g_hi[a];
        }
        if (outside) continue;
        const auto c0 = grid.cell_of(lo), c1 = grid.cell_of(hi);
        for (int z = c0[2]; z <= c1[2]; ++z)
          for (int y = c0[1]; y <= c1[1]; ++y)
            for (int x = c0[0]; x <= c1[0]; ++x)
              entries.push_back({static_cast<std::uint32_t>(grid.linear(x, y, z)), tri});
      }
      bins.start.assign(grid.n_cells() + 1, 0);
      for (const auto& e : entries) ++bins.start[e.first + 1];
      for (std::size_t c = 0; c < grid.n_cells(); ++c) bins.start[c + 1] += bins.start[c];
      bins.members.resize(entries.size());
      std::vector<std::uint32_t> fill(bins.start.begin(), bins.start.end() - 1);
      for (const auto& e : entries) bins.members[fill[e.first]++] = e.second;
      bins.valid = true;
      bins.reach = reach;
      bins.dims = dims;
      bins.origin = g_lo;
    }
    for (std::uint32_t i = 0; i < grains; ++i) {
      const std::size_t c = grid.cell_index(s.x[i]);
      const double within = s.radius[i] + range;
      const auto first = static_cast<std::uint32_t>(list.wall_elements.size());
      for (std::uint32_t m = bins.start[c]; m < bins.start[c + 1]; ++m) {
        const std::uint32_t tri = bins.members[m];
        const auto [lo, hi] = box_of(tri);
        double d2 = 0.0; // squared distance from the centre to the triangle's box
        for (int a = 0; a < 3; ++a) {
          const double p = s.x[i][a];
          const double out = p < lo[a] ? lo[a] - p : (p > hi[a] ? p - hi[a] : 0.0);
          d2 += out * out;
        }
        if (!(d2 < within * within)) continue;
        const auto& placed = mesh.placed[tri]; // and to its plane
        const double above = dot(placed.normal, s.x[i] - placed.a);
        if (above * above < within * within) list.wall_elements.push_back(tri);
      }
      const auto count = static_cast<std::uint32_t>(list.wall_elements.size()) - first;
      if (count > 0) list.walls.push_back({i, w, first, count});
    }
  }
  built_at_ = t;
}

void Walls::steer_servos(const Comm& comm, double t, double dt, std::int64_t step) {
  std::vector<double> along;
  std::vector<MeshWall*> servos;
  for (std::size_t w = 0; w < shaped_.size(); ++w) {
    auto* mesh = std::get_if<MeshWall>(&shaped_[w]);
    if (!mesh || !mesh->controller) continue;
    servos.push_back(mesh);
    along.push_back(w < shaped_loads_.size() ? -dot(shaped_loads_[w].force, mesh->servo_axis)
                                             : 0.0);
  }
  if (servos.empty()) return;
  comm.sum(along.data(), static_cast<int>(along.size()));
  for (std::size_t k = 0; k < servos.size(); ++k) {
    MeshWall& m = *servos[k];
    const double speed = m.controller->speed(along[k], t);
    if (!std::isfinite(speed))
      throw SimulationError(fmt::format("step {}, t = {}: the controller of wall '{}' gave the "
                                        "speed {}",
                                        step, t, m.name, speed));
    m.servo_speed = speed;
    m.servo_offset += speed * dt;
  }
}

void Walls::set_controller(std::size_t wall, std::shared_ptr<WallController> controller) {
  auto* mesh = wall < shaped_.size() ? std::get_if<MeshWall>(&shaped_[wall]) : nullptr;
  if (!mesh || !mesh->controller)
    throw std::invalid_argument(fmt::format(
        "wall {} is not a controlled mesh: give its [[mesh]] servo_force or controlled = true",
        wall < shaped_.size() ? fmt::format("'{}'", wall_name(shaped_[wall]))
                              : std::to_string(wall)));
  if (!controller) throw std::invalid_argument("a wall's controller cannot be empty");
  mesh->controller = std::move(controller);
}

std::pair<double, double> Walls::servo_state(std::size_t wall) const {
  const auto* mesh = wall < shaped_.size() ? std::get_if<MeshWall>(&shaped_[wall]) : nullptr;
  if (!mesh) return {0.0, 0.0};
  return {mesh->servo_speed, mesh->servo_offset};
}

void Walls::add_work(const std::vector<WallLoad>& plane_loads) {
  for (std::size_t w = 0; w < shaped_loads_.size(); ++w) work_.shaped[w] += shaped_loads_[w].work;
  if (!planes_.empty())
    for (std::size_t p = 0; p < plane_loads.size() && p < work_.planes.size(); ++p)
      work_.planes[p] += plane_loads[p].work;
}

std::vector<WallLoad> Walls::shaped_loads(const Comm& comm) const {
  std::vector<double> sums;
  for (std::size_t w = 0; w < shaped_.size(); ++w) {
    const WallLoad l = w < shaped_loads_.size() ? shaped_loads_[w] : WallLoad{};
    for (const double x : {l.force.x, l.force.y, l.force.z, l.torque.x, l.torque.y, l.torque.z,
                           work_.shaped[w], static_cast<double>(l.contacts)})
      sums.push_back(x);
  }
  if (!sums.empty()) comm.sum(sums.data(), static_cast<int>(sums.size()));
  std::vector<WallLoad> out(shaped_.size());
  for (std::size_t w = 0; w < shaped_.size(); ++w) {
    const double* s = sums.data() + 8 * w;
    out[w].force = {s[0], s[1], s[2]};
    out[w].torque = {s[3], s[4], s[5]};
    out[w].work = s[6];
    out[w].contacts = static_cast<std::size_t>(s[7]);
  }
  return out;
}

std::vector<WallLoad> Walls::plane_loads(const Comm& comm,
                                         const std::vector<WallLoad>& mine) const {
  std::vector<double> sums;
  for (std::size_t p = 0; p < planes_.size(); ++p) {
    const WallLoad l = p < mine.size() ? mine[p] : WallLoad{};
    const double work = p < work_.planes.size() ? work_.planes[p] : 0.0;
    for (const double x : {l.force.x, l.force.y, l.force.z, work, static_cast<double>(l.contacts)})
      sums.push_back(x);
  }
  if (!sums.empty()) comm.sum(sums.data(), static_cast<int>(sums.size()));
  std::vector<WallLoad> out(planes_.size());
  for (std::size_t p = 0; p < planes_.size(); ++p) {
    const double* s = sums.data() + 5 * p;
    out[p].force = {s[0], s[1], s[2]};
    out[p].work = s[3];
    out[p].contacts = static_cast<std::size_t>(s[4]);
  }
  return out;
}

std::vector<Vec3> Walls::triangle_forces(const Comm& comm, std::size_t wall) const {
  const auto* mesh = std::get_if<MeshWall>(&shaped_.at(wall));
  std::vector<Vec3> f(mesh ? mesh->whole_mesh().n_triangles() : 0);
  for (const ElementForce& e : element_forces_)
    if (e.wall == wall && e.element < f.size()) f[e.element] += e.force;
  if (!f.empty()) comm.sum(&f[0].x, static_cast<int>(3 * f.size()));
  return f;
}

void Walls::set_work(Work w) {
  work_ = std::move(w);
  work_.shaped.resize(shaped_.size(), 0.0);
  work_.planes.resize(planes_.size(), 0.0);
}

void Walls::sum_work_onto_root(const Comm& comm) {
  work_.shaped.resize(shaped_.size(), 0.0);
  if (!work_.shaped.empty()) comm.sum(work_.shaped.data(), static_cast<int>(work_.shaped.size()));
  if (!comm.root()) std::fill(work_.shaped.begin(), work_.shaped.end(), 0.0);
}

void Walls::save(ArchiveWriter& ar) const {
  std::vector<std::uint32_t> crcs;
  for (const ShapedWall& w : shaped_)
    crcs.push_back(std::holds_alternative<MeshWall>(w) ? std::get<MeshWall>(w).file_crc32 : 0);
  ar.vector(crcs);
  ar.value(built_at_);
  ar.vector(work_.shaped);
  ar.vector(work_.planes);
  std::vector<double> servo;
  for (const ShapedWall& w : shaped_)
    if (const auto* m = std::get_if<MeshWall>(&w))
      servo.insert(servo.end(), {m->servo_offset, m->servo_speed, m->servo_offset_built});
  ar.vector(servo);
}

void Walls::load(ArchiveReader& ar, std::uint32_t layout) {
  std::vector<std::uint32_t> crcs;
  ar.vector(crcs);
  check_files(crcs);
  ar.value(built_at_);
  ar.vector(work_.shaped);
  if (layout >= 6) ar.vector(work_.planes);
  work_.planes.resize(planes_.size(), 0.0);
  // Each mesh's servo: its offset and speed, and (from layout 7) its offset at the last build.
  const std::size_t per_mesh = layout < 7 ? 2 : 3;
  std::vector<double> servo;
  ar.vector(servo);
  std::size_t k = 0;
  for (ShapedWall& w : shaped_)
    if (auto* m = std::get_if<MeshWall>(&w)) {
      if (k + per_mesh > servo.size())
        throw std::invalid_argument("the checkpoint's walls are not this scene's");
      m->servo_offset = servo[k], m->servo_speed = servo[k + 1];
      m->servo_offset_built = per_mesh == 3 ? servo[k + 2] : servo[k];
      k += per_mesh;
    }
  if (work_.shaped.size() != shaped_.size())
    throw std::invalid_argument("the checkpoint's walls are not this scene's");
}

void Walls::check_files(const std::vector<std::uint32_t>& saved) const {
  if (saved.size() != shaped_.size())
    throw std::invalid_argument(fmt::format(
        "the checkpoint has {} meshes and cylinders, this scene {}", saved.size(), shaped_.size()));
  for (std::size_t w = 0; w < shaped_.size(); ++w) {
    const auto* mesh = std::get_if<MeshWall>(&shaped_[w]);
    if (mesh && mesh->file_crc32 != saved[w])
      throw std::invalid_argument(fmt::format(
          "mesh '{}': its file {} has changed since the checkpoint was written (CRC-32 {:08x}, "
          "then {:08x}); resuming would not continue the same run",
          mesh->name, mesh->file, mesh->file_crc32, saved[w]));
  }
}

Walls::AsBuilt Walls::stand_as_built() {
  AsBuilt as_built{built_at_, {}};
  for (ShapedWall& w : shaped_)
    if (auto* m = std::get_if<MeshWall>(&w))
      as_built.servo_now.push_back(std::exchange(m->servo_offset, m->servo_offset_built));
  place_shaped(built_at_, true);
  return as_built;
}

void Walls::stand_again(const AsBuilt& as_built, double t) {
  built_at_ = as_built.built_at;
  std::size_t k = 0;
  for (ShapedWall& w : shaped_)
    if (auto* m = std::get_if<MeshWall>(&w)) m->servo_offset = as_built.servo_now[k++];
  place_shaped(t, true);
}

void Walls::mark_materials(std::vector<bool>& present) const {
  for (const PlaneWall& p : planes_)
    if (p.material < present.size()) present[p.material] = true;
  for (const ShapedWall& w : shaped_)
    if (wall_material(w) < present.size()) present[wall_material(w)] = true;
}

std::string Walls::describe_deep_start(const DeepStarts& deep) const {
  const ShapedWall& wall = shaped_[deep.wall];
  const std::string element =
      std::holds_alternative<MeshWall>(wall)
          ? fmt::format("triangle {}", deep.element)
          : fmt::format("patch {} (0 the side, 1 and 2 the caps)", deep.element);
  return fmt::format("the one that began with the most energy ({:.4g}) began at t = {:.6g} on wall "
                     "'{}', {}, against grain {}, overlapping it by {:.4g} where the grain had "
                     "come {:.4g} nearer the wall in the step",
                     deep.worst, deep.time, wall_name(wall), element, deep.grain, deep.overlap,
                     deep.approach);
}

} // namespace yuxi
