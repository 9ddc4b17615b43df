// The walls of a simulation, one part of it: everything that bounds the grains but grains.
// Three kinds, each with one name throughout the engine:
//   wall particles  particles of Kind::wall in the particle store, carried by their prescribed
//                   motions (motions(); scene/wall_motion.hpp)
//   planes          flat walls (PlaneWall): the scene's, then the box's walled faces
//   shaped walls    triangle meshes and analytic cylinders (ShapedWall)
// The part owns them and their state: the meshes' triangles binned on the cells and the part
// of each mesh a rank holds, where each moving shaped wall stood at the last list build, the
// loads and element forces of the last force evaluation, each wall's cumulative work, and the
// servos. It places them at every step, lists the grains' candidate triangles at a list build
// (walls.cpp) and saves its section of a checkpoint.
//
// A mesh's triangles are binned into every cell that their box, grown by the largest grain
// radius and the skin, overlaps; a grain then reads the triangles of its own cell only, so the
// cost per grain does not grow with the size of the mesh, and triangles far from every grain
// cost nothing per step. A still mesh keeps its bins while the cells stay the same. A rank
// holds (places, bins, searches) only the triangles of a mesh that lie near its own grains,
// chosen again from the whole mesh when the grains leave the box they were chosen for, or at
// every build if the mesh moves (MeshWall::hold_near).
#pragma once

#include "core/archive.hpp"
#include "core/cell_grid.hpp"
#include "core/neighbor_list.hpp"
#include "core/particle_store.hpp"
#include "domain/comm.hpp"
#include "scene/plane_wall.hpp"
#include "scene/shaped_wall.hpp"
#include "scene/wall_motion.hpp"
#include "sim/contact_tally.hpp"
#include "sim/simulation_config.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace yuxi {

class Walls {
public:
  // The box's walled faces are added after the scene's planes; no motion means one at rest.
  Walls(const SimulationConfig& config, std::vector<PlaneWall> planes,
        std::vector<WallMotion> motions, std::vector<ShapedWall> shaped);

  // The reach of the list: the skin and the edge of the linked cells [length].
  void size_for(double skin, double cell_edge) {
    skin_ = skin;
    cell_edge_ = cell_edge;
  }

  const std::vector<PlaneWall>& planes() const { return planes_; }
  const std::vector<WallMotion>& motions() const { return motions_; }
  const std::vector<ShapedWall>& shaped() const { return shaped_; }
  // Every wall particle at rest at the last place() (they do no work).
  bool particles_still() const { return particles_still_; }

  // Wall particles and shaped walls to their place at t; true if one moved more than half the
  // skin since the last list build. `every_one` false skips those of a motion at rest: placed
  // before, they stay there. `moved2`, if given, gets the largest squared displacement of a
  // wall particle.
  bool place(ParticleStore& s, double t, bool every_one, double* moved2 = nullptr);
  // The shaped walls alone.
  bool place_shaped(double t, bool every_one);
  // At a list build: the grains [0, n_grains) that may touch each shaped wall before the next,
  // with their candidate triangles, into list.walls and list.wall_elements (the triangles
  // binned on `grid`, reused while they hold). `range`: the list's reach beyond touching.
  void list_candidates(const ParticleStore& s, std::size_t n_grains, const CellGrid& grid,
                       double range, double t, NeighborList& list);

  // Servo-controlled meshes: each controller is told the grains' force on its wall (summed
  // over the ranks: one reduction per step, only where such walls are) and sets the wall's
  // speed for the next step; the wall moves by it over that step. Throws SimulationError on a
  // controller's speed that is not finite. Collective where such walls are.
  void steer_servos(const Comm& comm, double t, double dt, std::int64_t step);
  // The shaped walls' controlled meshes: another controller (throws std::invalid_argument if
  // `wall` is not a controlled mesh), and the speed along its axis and distance moved.
  void set_controller(std::size_t wall, std::shared_ptr<WallController> controller);
  std::pair<double, double> servo_state(std::size_t wall) const;

  // What the last force evaluation did on this rank, written by the contact computation: each
  // shaped wall's load and each contact's force on its triangle or patch.
  std::vector<WallLoad>& shaped_loads_here() { return shaped_loads_; }
  std::vector<ElementForce>& element_forces_here() { return element_forces_; }
  // After a step's forces: each wall's work in it added to its cumulative work (the planes'
  // from `plane_loads`, this rank's loads of the planes).
  void add_work(const std::vector<WallLoad>& plane_loads);

  // Summed over the ranks onto every rank. Collective.
  // Each shaped wall's load at the last force evaluation, with its cumulative work.
  std::vector<WallLoad> shaped_loads(const Comm& comm) const;
  // The same for the planes, from this rank's `mine` (torque zero).
  std::vector<WallLoad> plane_loads(const Comm& comm, const std::vector<WallLoad>& mine) const;
  // The force on each triangle of mesh `wall` (zero where nothing touches).
  std::vector<Vec3> triangle_forces(const Comm& comm, std::size_t wall) const;

  // This rank's part of each wall's cumulative work.
  struct Work {
    std::vector<double> shaped, planes;
  };
  const Work& work() const { return work_; }
  void set_work(Work w);
  // After loading several ranks' sections: the work summed onto rank 0. Collective.
  void sum_work_onto_root(const Comm& comm);

  // The walls' section of a checkpoint: each mesh file's CRC-32 (a resume with another file is
  // refused), the time of the last list build (where the meshes stood), the work of each
  // wall, each mesh's servo (its offset and speed, and its offset at the last list build).
  // Loading reads layouts back to oldest_state_layout, and throws std::invalid_argument where
  // the walls are not this scene's.
  void save(ArchiveWriter& ar) const;
  void load(ArchiveReader& ar, std::uint32_t layout);

  // A list build made again where the run's last one was (a resume bit for bit): the shaped
  // walls stand as they stood then, servos where they had carried their meshes then; after
  // it, stand_again() puts them back where they stand at t.
  struct AsBuilt {
    double built_at = 0.0;
    std::vector<double> servo_now;
  };
  AsBuilt stand_as_built();
  void stand_again(const AsBuilt& as_built, double t);

  // Marks the materials of the planes and shaped walls (indices below present.size()).
  void mark_materials(std::vector<bool>& present) const;
  // Where the wall contact that began deepest began (DeepStarts), for a diagnosis.
  std::string describe_deep_start(const DeepStarts& deep) const;

private:
  void check_files(const std::vector<std::uint32_t>& saved) const;

  // Each mesh's triangles binned on the cells (CSR by cell), reused while a still mesh and the
  // cells stay as they were.
  struct MeshBins {
    std::vector<std::uint32_t> start, members;
    bool valid = false;
    double reach = 0.0;
    Vec3 origin;
    std::array<int, 3> dims{};
    // The box (the grains' grown by a cell edge) and the reach for which a mesh's held
    // triangles were chosen.
    Vec3 held_lo, held_hi;
    double held_reach = -1.0;
  };

  std::vector<PlaneWall> planes_;
  std::vector<WallMotion> motions_;
  std::vector<ShapedWall> shaped_;
  double skin_ = 0.0, cell_edge_ = 0.0;
  bool particles_still_ = false;
  std::vector<WallLoad> shaped_loads_;       // this rank's, of the last force evaluation
  std::vector<ElementForce> element_forces_; // this rank's wall contacts, of the same
  Work work_;
  std::vector<MeshBins> mesh_bins_;
  // Each moving mesh's vertices (where a rank holds a part of it, the held vertices), or
  // moving cylinder's shift, at the last list build.
  std::vector<std::vector<Vec3>> x_built_;
  double built_at_ = 0.0; // time of the last list build
  // Each motion at the time being placed, and whether its particles are at rest (kept between
  // steps: a step allocates nothing).
  std::vector<WallMotionAtTime> now_;
  std::vector<std::uint8_t> skip_;
};

} // namespace yuxi
