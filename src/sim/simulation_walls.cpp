// Shaped walls in the simulation: placing the meshes and cylinders at each step, binning the
// meshes' triangles on the linked cells at a list build, and listing which grains may touch
// which wall (and which of its triangles) before the next build.
//
// A mesh's triangles are binned into every cell that their box, grown by the largest grain
// radius and the skin, overlaps; a grain then reads the triangles of its own cell only, so the
// cost per grain does not grow with the size of the mesh, and triangles far from every grain
// cost nothing per step. A still mesh keeps its bins while the cells stay the same. A rank
// holds (places, bins, searches) only the triangles of a mesh that lie near its own grains,
// chosen again from the whole mesh when the grains leave the box they were chosen for, or at
// every build if the mesh moves (MeshWall::hold_near).
#include "sim/simulation.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <limits>
#include <span>

namespace yuxi {

bool Simulation::place_shaped_walls(double t, bool every_one) {
  const double limit2 = 0.25 * config_.skin * config_.skin;
  bool moved_far = false;
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const auto& built = mesh_x_build_[w];
    if (auto* cylinder = std::get_if<CylinderWall>(&walls_[w])) {
      if (!every_one && !cylinder->moves()) continue;
      cylinder->place(t);
      if (built.size() == 1 && !(norm2(cylinder->shift - built[0]) <= limit2)) moved_far = true;
      continue;
    }
    auto& mesh = std::get<MeshWall>(walls_[w]);
    if (!every_one && !mesh.moves()) continue;
    mesh.place(t);
    // Its vertices; where this rank holds a part of it, the held vertices, and the bound on
    // every point's displacement (MeshWall::moved2_since_build): a triangle left out lay a cell
    // edge beyond the reach of the grains' box at the build (list_wall_candidates), and comes
    // within it only after it has moved that much farther than half the skin.
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
      const double far = 0.5 * config_.skin + cell_edge_;
      moved_far = moved_far || moved_beyond(built, mesh.x, limit2) ||
                  !(mesh.moved2_since_build() <= far * far);
    }
  }
  return moved_far;
}

void Simulation::list_wall_candidates() {
  list_.walls.clear();
  list_.wall_elements.clear();
  if (walls_.empty()) return;
  // The largest radius, and the box of the grains' centres (empty without grains).
  double largest = 0.0;
  constexpr double inf = std::numeric_limits<double>::infinity();
  Vec3 grains_lo{inf, inf, inf}, grains_hi{-inf, -inf, -inf};
  for (std::size_t i = 0; i < owned_grains_; ++i) {
    largest = std::max(largest, store_.radius[i]);
    for (int a = 0; a < 3; ++a) {
      grains_lo[a] = std::min(grains_lo[a], store_.x[i][a]);
      grains_hi[a] = std::max(grains_hi[a], store_.x[i][a]);
    }
  }
  const double reach = largest + range_;
  const Vec3 g_lo = grid_.origin(), edge = grid_.edge();
  const auto dims = grid_.dims();
  const Vec3 g_hi{g_lo.x + dims[0] * edge.x, g_lo.y + dims[1] * edge.y, g_lo.z + dims[2] * edge.z};
  for (std::uint32_t w = 0; w < walls_.size(); ++w) {
    if (const auto* cylinder = std::get_if<CylinderWall>(&walls_[w])) {
      if (cylinder->moves()) mesh_x_build_[w].assign(1, cylinder->shift);
      WallTouches near;
      for (std::uint32_t i = 0; i < owned_grains_; ++i) {
        cylinder->touches(store_.x[i], store_.radius[i] + range_, near);
        if (near.n > 0) list_.walls.push_back({i, w, 0, 0});
      }
      continue;
    }
    MeshWall& mesh = std::get<MeshWall>(walls_[w]);
    MeshBins& bins = mesh_bins_[w];
    // Of a mesh, this rank holds only the triangles its grains can reach: those within the
    // reach of the grains' box grown by a cell edge. Chosen again, where the mesh stands now,
    // at every build if it moves (see place_shaped_walls), else when the grains leave that box
    // or the reach grows.
    bool inside = bins.held_reach >= reach;
    for (int a = 0; a < 3; ++a)
      inside = inside && grains_lo[a] >= bins.held_lo[a] && grains_hi[a] <= bins.held_hi[a];
    if (mesh.moves() || !inside) {
      bins.held_reach = std::max(reach, cell_edge_ + range_);
      bins.held_lo = grains_lo - Vec3{cell_edge_, cell_edge_, cell_edge_};
      bins.held_hi = grains_hi + Vec3{cell_edge_, cell_edge_, cell_edge_};
      if (mesh.hold_near(bins.held_lo, bins.held_hi, bins.held_reach)) bins.valid = false;
    }
    if (mesh.x.size() != mesh.mesh.vertices.size()) mesh.place(time_);
    mesh.mark_built();
    if (mesh.moves()) mesh_x_build_[w] = mesh.x; // (a still mesh never moves from its build)
    // Each triangle's box, as placed now.
    const auto box_of = [&](std::uint32_t t) { return mesh.mesh.box_of(t, mesh.x); };
    if (mesh.moves() || !bins.valid || bins.reach < reach || bins.dims != dims ||
        bins.origin != g_lo) {
      // Counting sort of (cell, triangle) by cell; triangles ascend within a cell.
      std::vector<std::pair<std::uint32_t, std::uint32_t>> entries;
      for (std::uint32_t t = 0; t < mesh.mesh.n_triangles(); ++t) {
        auto [lo, hi] = box_of(t);
        bool outside = false;
        for (int a = 0; a < 3; ++a) {
          lo[a] -= reach, hi[a] += reach;
          outside = outside || hi[a] < g_lo[a] || lo[a] > g_hi[a];
        }
        if (outside) continue;
        const auto c0 = grid_.cell_of(lo), c1 = grid_.cell_of(hi);
        for (int z = c0[2]; z <= c1[2]; ++z)
          for (int y = c0[1]; y <= c1[1]; ++y)
            for (int x = c0[0]; x <= c1[0]; ++x)
              entries.push_back({static_cast<std::uint32_t>(grid_.linear(x, y, z)), t});
      }
      bins.start.assign(grid_.n_cells() + 1, 0);
      for (const auto& e : entries) ++bins.start[e.first + 1];
      for (std::size_t c = 0; c < grid_.n_cells(); ++c) bins.start[c + 1] += bins.start[c];
      bins.members.resize(entries.size());
      std::vector<std::uint32_t> fill(bins.start.begin(), bins.start.end() - 1);
      for (const auto& e : entries) bins.members[fill[e.first]++] = e.second;
      bins.valid = true;
      bins.reach = reach;
      bins.dims = dims;
      bins.origin = g_lo;
    }
    for (std::uint32_t i = 0; i < owned_grains_; ++i) {
      const std::size_t c = grid_.cell_index(store_.x[i]);
      const double within = store_.radius[i] + range_;
      const auto first = static_cast<std::uint32_t>(list_.wall_elements.size());
      for (std::uint32_t m = bins.start[c]; m < bins.start[c + 1]; ++m) {
        const std::uint32_t t = bins.members[m];
        const auto [lo, hi] = box_of(t);
        double d2 = 0.0; // squared distance from the centre to the triangle's box
        for (int a = 0; a < 3; ++a) {
          const double p = store_.x[i][a];
          const double out = p < lo[a] ? lo[a] - p : (p > hi[a] ? p - hi[a] : 0.0);
          d2 += out * out;
        }
        if (!(d2 < within * within)) continue;
        const auto& placed = mesh.placed[t]; // and to its plane
        const double above = dot(placed.normal, store_.x[i] - placed.a);
        if (above * above < within * within) list_.wall_elements.push_back(t);
      }
      const auto count = static_cast<std::uint32_t>(list_.wall_elements.size()) - first;
      if (count > 0) list_.walls.push_back({i, w, first, count});
    }
  }
  walls_built_at_ = time_;
}

void Simulation::check_wall_files(const std::vector<std::uint32_t>& saved) const {
  if (saved.size() != walls_.size())
    throw std::invalid_argument(fmt::format(
        "the checkpoint has {} meshes and cylinders, this scene {}", saved.size(), walls_.size()));
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const auto* mesh = std::get_if<MeshWall>(&walls_[w]);
    if (mesh && mesh->file_crc32 != saved[w])
      throw std::invalid_argument(fmt::format(
          "mesh '{}': its file {} has changed since the checkpoint was written (CRC-32 {:08x}, "
          "then {:08x}); resuming would not continue the same run",
          mesh->name, mesh->file, mesh->file_crc32, saved[w]));
  }
}

std::vector<WallLoad> Simulation::wall_loads() const {
  std::vector<double> sums;
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const WallLoad l = w < wall_loads_.size() ? wall_loads_[w] : WallLoad{};
    for (const double x : {l.force.x, l.force.y, l.force.z, l.torque.x, l.torque.y, l.torque.z,
                           wall_work_[w], static_cast<double>(l.contacts)})
      sums.push_back(x);
  }
  if (!sums.empty()) comm_.sum(sums.data(), static_cast<int>(sums.size()));
  std::vector<WallLoad> out(walls_.size());
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const double* s = sums.data() + 8 * w;
    out[w].force = {s[0], s[1], s[2]};
    out[w].torque = {s[3], s[4], s[5]};
    out[w].work = s[6];
    out[w].contacts = static_cast<std::size_t>(s[7]);
  }
  return out;
}

std::vector<WallLoad> Simulation::plane_loads() const {
  const std::vector<WallLoad>& mine = std::visit(
      [](const auto& f) -> const std::vector<WallLoad>& { return f.plane_loads; }, forces_);
  std::vector<double> sums;
  for (std::size_t p = 0; p < planes_.size(); ++p) {
    const WallLoad l = p < mine.size() ? mine[p] : WallLoad{};
    const double work = p < plane_work_.size() ? plane_work_[p] : 0.0;
    for (const double x : {l.force.x, l.force.y, l.force.z, work, static_cast<double>(l.contacts)})
      sums.push_back(x);
  }
  if (!sums.empty()) comm_.sum(sums.data(), static_cast<int>(sums.size()));
  std::vector<WallLoad> out(planes_.size());
  for (std::size_t p = 0; p < planes_.size(); ++p) {
    const double* s = sums.data() + 5 * p;
    out[p].force = {s[0], s[1], s[2]};
    out[p].work = s[3];
    out[p].contacts = static_cast<std::size_t>(s[4]);
  }
  return out;
}

void Simulation::steer_servo_walls() {
  std::vector<double> along;
  std::vector<MeshWall*> servos;
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    auto* mesh = std::get_if<MeshWall>(&walls_[w]);
    if (!mesh || !mesh->controller) continue;
    servos.push_back(mesh);
    along.push_back(w < wall_loads_.size() ? -dot(wall_loads_[w].force, mesh->servo_axis) : 0.0);
  }
  if (servos.empty()) return;
  comm_.sum(along.data(), static_cast<int>(along.size()));
  for (std::size_t k = 0; k < servos.size(); ++k) {
    MeshWall& m = *servos[k];
    const double speed = m.controller->speed(along[k], time_);
    if (!std::isfinite(speed))
      throw SimulationError(fmt::format("step {}, t = {}: the controller of wall '{}' gave the "
                                        "speed {}",
                                        step_, time_, m.name, speed));
    m.servo_speed = speed;
    m.servo_offset += speed * config_.dt;
  }
}

std::vector<Vec3> Simulation::triangle_forces(std::size_t wall) const {
  const auto* mesh = std::get_if<MeshWall>(&walls_.at(wall));
  std::vector<Vec3> f(mesh ? mesh->whole_mesh().n_triangles() : 0);
  for (const ElementForce& e : element_forces_)
    if (e.wall == wall && e.element < f.size()) f[e.element] += e.force;
  if (!f.empty()) comm_.sum(&f[0].x, static_cast<int>(3 * f.size()));
  return f;
}

} // namespace yuxi
