// The fish-basin analysis during a run (docs/models/fish-basin.md section 7), from the scene's
// [analysis] table: at the requested times and over the first excitation period it computes, on
// every rank from its own grains, the free surface (Figs. 5-6), the velocities in the vertical
// plane through two antinodes (Fig. 7), the elastic energy summed over z (Fig. 8), the energy
// densities of horizontal slabs, coarse-grained and averaged over the period (Fig. 9) and the
// densities of per-grain kinetic, elastic and total energy with power-law fits (Fig. 10). Grids and
// histograms are reduced over ranks (no particle is gathered), and rank 0 writes CSV files into
// <run>/analysis/; plots/plot_basin.py draws the figures from them. At regular intervals it also
// follows the surface's peaks and profiles along the antinodes and nodes (peaks.csv,
// surface_profile.csv), the elastic energy's profiles (elastic_profile.csv), and saves every
// grain's energies (grains/grains_t<time>.npy, which every rank writes its part of).
#pragma once

#include "analysis/column_sum.hpp"
#include "analysis/power_law.hpp"
#include "analysis/section_energies.hpp"
#include "analysis/sector_profile.hpp"
#include "analysis/xy_grid.hpp"
#include "io/energy_csv.hpp"
#include "io/scene.hpp"
#include "sim/simulation.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <vector>

namespace yuxi {

class RunAnalysis {
public:
  // The scene must have an [analysis] table (its reader resolved the averaging window).
  // `resume_after`: a resumed run continues the time series of the saved run up to this step.
  RunAnalysis(const Scene& scene, std::filesystem::path dir, double dt,
              std::optional<std::int64_t> resume_after = std::nullopt);

  // Before a step: records contacts when the step ends at a sample that needs elastic energy.
  void before_step(Simulation& sim) const;
  // After a step: computes and writes what is due at the simulation's step. Collective.
  void after_step(Simulation& sim);
  // The first step after `step` at which after_step has something to do (the largest step when
  // none): an engine that runs many steps in one go (the device engine) stops there.
  std::int64_t next_step_after(std::int64_t step) const;
  // Where the per-grain elastic energies come from (by default particle_elastic_energy, from
  // the contact record that before_step asks for): the owned particles', in their order.
  void set_elastic_energy(std::function<std::vector<double>(Simulation&)> source);
  // Writes the period averages, densities and fits (if the window was sampled). Collective.
  void finish(Simulation& sim);

private:
  struct Grains { // the owned grains of this rank
    std::vector<Vec3> x, v;
    std::vector<double> radius, mass, kinetic, elastic;
    std::vector<GlobalId> id;
  };
  // Steps first, first + every, ... up to last (none when every is 0).
  struct Every {
    std::int64_t first = 0, last = -1, every = 0;
    bool due(std::int64_t step) const {
      return every > 0 && step >= first && step <= last && (step - first) % every == 0;
    }
    // The first due step after `step` (the largest step when none).
    std::int64_t next_after(std::int64_t step) const;
  };
  Grains grains(Simulation& sim, bool energies) const;
  // The free surface, and the column-summed elastic energy, of every rank's grains (reduced
  // onto every rank). Collective.
  analysis::GridField surface(Simulation& sim, const Grains& g) const;
  analysis::GridField elastic_columns(Simulation& sim, const Grains& g) const;
  void write_surface(Simulation& sim, const Grains& g) const;
  void write_velocity_section(Simulation& sim, const Grains& g) const;
  void write_elastic_map(Simulation& sim, const Grains& g) const;
  void write_tracks(Simulation& sim, const Grains& g);
  void write_waves(Simulation& sim, const Grains& g);
  void write_grain_sample(Simulation& sim, const Grains& g) const;
  // Rows "step,time,direction,r_lo,r_hi,columns,mean,median,max" of a field's radial profiles
  // along the antinodes and the nodes.
  void write_profiles(EnergyCsv& csv, const Simulation& sim, const analysis::GridField& f) const;
  // A time series of analysis/<name>, opened on rank 0 at its first row.
  EnergyCsv& series(std::unique_ptr<EnergyCsv>& csv, const char* name, const char* header);
  void accumulate_period(const Grains& g);
  bool period_sample(std::int64_t step) const; // a sample step of the averaging window
  bool needs_energies(std::int64_t step) const;

  std::function<std::vector<double>(Simulation&)> elastic_energy_;
  AnalysisSettings settings_;
  std::filesystem::path dir_;
  analysis::XYGrid grid_;
  Vec3 axis_;
  std::set<std::int64_t> surface_steps_, velocity_steps_, elastic_steps_;
  std::int64_t period_first_ = 0, period_last_ = -1, period_every_ = 1;
  analysis::LogHistogram pdf_kinetic_, pdf_elastic_, pdf_total_;
  analysis::SectionEnergies sections_; // Fig. 9
  analysis::ModeSectors sectors_;
  Every track_, wave_, sample_;
  std::optional<std::int64_t> resume_after_;
  std::unique_ptr<EnergyCsv> peaks_, surface_profile_, elastic_profile_;
  bool finished_ = false;
};

} // namespace yuxi
