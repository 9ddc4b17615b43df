// A scene file, parsed once into typed structs. Every field has its default here; the reader
// fills what the file gives and validates it, the writer echoes the resolved scene.
#pragma once

#include "contact/contact_model.hpp"
#include "scene/clump_shape.hpp"
#include "scene/coarse_grain_spec.hpp"
#include "scene/fish_basin.hpp"
#include "scene/measure_spec.hpp"
#include "scene/particle_fill.hpp"
#include "scene/particle_source.hpp"
#include "scene/plane_wall.hpp"
#include "scene/shaped_wall.hpp"
#include "sim/simulation_config.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace yuxi {

// The engine that steps a run (docs/gpu.md): the CPU engine; the device engine on a GPU; or the
// device engine's code on the CPU (host), the reference the GPU is tested against.
enum class RunDevice { cpu, gpu, host };

struct RunSettings {
  std::string name = "yuxi";
  double t_end = 1.0;          // simulated time to reach [time]
  bool allow_large_dt = false; // accept dt > t_c / 10
  RunDevice device = RunDevice::cpu;
};

// "cpu", "gpu" or "host"; and back (std::nullopt for another word).
const char* run_device_name(RunDevice device);
std::optional<RunDevice> run_device_named(std::string_view name);

struct OutputSettings {
  double energy_interval = 0.01;  // time between rows of energies.csv [time]
  double snapshot_interval = 0.5; // time between VTK / dump frames; 0 = none [time]
  bool vtk = true;
  bool lammps_dump = true;
};

struct CheckpointSettings {
  std::int64_t every_steps = 0; // 0: not by step count
  double every_minutes = 10.0;  // of wall time; 0: not by time
  int keep = 3;                 // newest checkpoints kept
};

// Elastic properties of a material, needed by models that mix them (Hertz-Mindlin). NaN where
// the scene does not give them; youngs_modulus may be infinite (a rigid wall).
struct MaterialProperties {
  double youngs_modulus = std::numeric_limits<double>::quiet_NaN(); // E [force/length^2]
  double poisson_ratio = std::numeric_limits<double>::quiet_NaN();  // nu [-]
  double density = std::numeric_limits<double>::quiet_NaN();        // [mass/length^3]
};

// Particles read from a LAMMPS data file (atom_style sphere).
struct LammpsDataSpec {
  std::string file;                        // as resolved against the scene's folder
  std::vector<std::uint8_t> type_material; // material of each atom type (1-based types)
  std::vector<bool> frozen;                // per type: frozen atoms become fixed wall particles
  std::vector<std::int64_t> frozen_types;  // as given, for the echo
};

// What the fish-basin analysis computes during a run (docs/models/fish-basin.md section 7; the
// figures are drawn by plots/plot_basin.py from the CSV files it writes into <run>/analysis/).
struct AnalysisSettings {
  std::array<int, 2> grid{48, 48};       // x-y cells of the maps over the domain
  std::vector<double> surface_times;     // Fig. 5-6: free surface [time]
  std::vector<double> velocity_times;    // Fig. 7: velocities in the vertical plane
  double section_half_thickness = 1.5;   // of that plane [length]
  double section_azimuth = 0.0;          // of that plane [rad]; 0 passes through antinodes
  std::vector<double> elastic_map_times; // Fig. 8: elastic energy summed over z
  double period_start = -1;              // Fig. 9-10: averaging window [time]; < 0: the
  double period_length = -1;             // basin's first excitation period
  double sample_interval = 0.001;        // between samples in the window [time]
  std::vector<double> section_heights;   // Fig. 9: z0, z1 of each horizontal slab, in pairs
  double section_width = 0.0; // Fig. 9's coarse-graining: 0 bins of the grid, else a Gaussian's w
  std::array<double, 2> pdf_range{1e-4, 1e6}; // Fig. 10: energies binned [energy]
  int bins_per_decade = 10;
  std::array<double, 2> fit_a{0.2, 2.0}; // the paper's two power-law ranges
  std::array<double, 2> fit_b{10.0, 1e4};
  // The excitation's sectors (analysis/sector_profile.hpp): the mode m, the container's inner
  // radius and each wedge's half-width. m and the radius come from [basin].
  int mode = 2;
  double r_max = 0;             // [length]; 0: the domain's half-width in x
  double sector_half_width = 0; // [degrees]; 0: 45 / m (antinode and node wedges meet)
  double profile_bin = 0;       // radial bin [length]; 0: the grid's column width
  // Fig. 6, peaks that travel: every track_interval from period_start to track_until, the free
  // surface's highest column in each antinode sector (peaks.csv) and its radial profiles along
  // the antinodes and the nodes (surface_profile.csv).
  double track_interval = 0; // [time]; 0: none
  double track_until = -1;   // [time]; < 0: the run's end
  // Fig. 8, elastic waves: every wave_interval from period_start to wave_until, radial profiles
  // of the column-summed elastic energy along the antinodes and the nodes (elastic_profile.csv).
  double wave_interval = 0; // [time]; 0: none
  double wave_until = -1;   // [time]; < 0: period_start + 8 periods
  // Fig. 10, the saved samples: every grain_sample_interval between grain_samples_from and
  // grain_samples_until, every grain's position, radius, mass, kinetic and elastic energy in
  // analysis/grains/grains_t<time>.npy (numpy.load).
  double grain_sample_interval = 0; // [time]; 0: none
  double grain_samples_from = -1;   // [time]; < 0: period_start
  double grain_samples_until = -1;  // [time]; < 0: the end of the averaging window
};

// A [[clump]]: one clump of a [[shape]] placed where the scene says (docs/scene-format.md,
// "Clumps"): its centre of mass at `position`, the shape as written in its table turned by
// `orientation` about it and scaled by `scale`, moving at `velocity` and turning at
// `angular_velocity` (lab frame) [length/time, rad/time].
struct ClumpSpec {
  std::int32_t shape = -1; // the index of the [[shape]]
  double scale = 1.0;
  Vec3 position;
  Quaternion orientation; // the table's frame -> lab
  Vec3 velocity, angular_velocity;
  std::uint8_t material = 0;
  double density = 0.0; // [mass/length^3]
};

struct Scene {
  std::string source;      // file the scene was read from (for messages)
  std::string dt_location; // "file:line:column" of run.dt, for the time-step check
  RunSettings run;
  OutputSettings output;
  CheckpointSettings checkpoint;
  SimulationConfig sim;
  std::vector<std::string> materials;
  std::vector<MaterialProperties> material_properties; // parallel to materials
  std::string contact_model = "linear";
  std::string contact_preset = "paper";
  AnyContactLaw law;
  std::vector<PlaneWall> planes;
  std::vector<ShapedWall> walls;     // [[mesh]] and [[cylinder]], in file order
  std::vector<std::string> warnings; // for the user, once (e.g. mesh triangles left out)
  std::optional<FishBasinSpec> basin;
  std::optional<AnalysisSettings> analysis;
  std::vector<ClumpShape> shapes;                       // [[shape]]: clumps of spheres, by name
  std::vector<std::vector<SphereMember>> shape_spheres; // each shape's members as given, scaled
  std::vector<ClumpSpec> clumps;                        // [[clump]]: clumps placed one by one
  std::vector<FillSpec> fills;                          // [[fill]]: grains placed at the start
  std::vector<InsertSpec> inserts;                      // [[insert]]: grains poured during the run
  std::vector<OutletSpec> outlets;                      // [[outlet]]: where grains leave
  std::vector<MeasureSpec> measures;                    // [[measure]]: measurements.csv
  std::vector<CoarseGrainSpec> coarse_grains;           // [[coarse_grain]]: fields on grids
  std::vector<ParticleSpec> particles; // explicit [[particle]] entries and LAMMPS data atoms
  std::optional<LammpsDataSpec> lammps_data;
  std::size_t n_lammps_atoms = 0;
  // The largest radius of the grains the scene builds or pours (0: none; a branch takes its
  // grains from a checkpoint), and whether the skin is the default fraction of its diameter.
  double largest_grain_radius = 0.0;
  bool skin_from_grains = false;

  std::optional<std::uint8_t> material_index(const std::string& name) const {
    for (std::size_t k = 0; k < materials.size(); ++k)
      if (materials[k] == name) return static_cast<std::uint8_t>(k);
    return std::nullopt;
  }
};

} // namespace yuxi
