// The fish-basin analysis during a run (docs/models/fish-basin.md section 7), from the scene's
// [analysis] table: at the requested times and over the first excitation period it computes, on
// every rank from its own grains, the free surface (Figs. 5-6), the velocities in the vertical
// plane through two antinodes (Fig. 7), the elastic energy summed over z (Fig. 8), the energies of
// horizontal slabs averaged over the period (Fig. 9) and the densities of per-grain kinetic,
// elastic and total energy with power-law fits (Fig. 10). Grids and histograms are reduced
// over ranks (no particle is gathered), and rank 0 writes CSV files into <run>/analysis/;
// scripts/plot_basin.py draws the figures from them.
#pragma once

#include "analysis/column_sum.hpp"
#include "analysis/power_law.hpp"
#include "analysis/xy_grid.hpp"
#include "io/scene.hpp"
#include "sim/simulation.hpp"

#include <cstdint>
#include <filesystem>
#include <set>
#include <vector>

namespace yuxi {

class RunAnalysis {
public:
  // The scene must have an [analysis] table (its reader resolved the averaging window).
  RunAnalysis(const Scene& scene, std::filesystem::path dir, double dt);

  // Before a step: records contacts when the step ends at a sample that needs elastic energy.
  void before_step(Simulation& sim) const;
  // After a step: computes and writes what is due at the simulation's step. Collective.
  void after_step(Simulation& sim);
  // Writes the period averages, densities and fits (if the window was sampled). Collective.
  void finish(Simulation& sim);

private:
  struct Grains { // the owned grains of this rank
    std::vector<Vec3> x, v;
    std::vector<double> radius, kinetic, elastic;
  };
  Grains grains(Simulation& sim, bool energies) const;
  void write_surface(Simulation& sim, const Grains& g) const;
  void write_velocity_section(Simulation& sim, const Grains& g) const;
  void write_elastic_map(Simulation& sim, const Grains& g) const;
  void accumulate_period(const Grains& g);
  bool period_sample(std::int64_t step) const; // a sample step of the averaging window
  bool needs_energies(std::int64_t step) const;

  AnalysisSettings settings_;
  std::filesystem::path dir_;
  analysis::XYGrid grid_;
  Vec3 axis_;
  std::set<std::int64_t> surface_steps_, velocity_steps_, elastic_steps_;
  std::int64_t period_first_ = 0, period_last_ = -1, period_every_ = 1;
  std::vector<analysis::ColumnAccumulator> section_elastic_, section_kinetic_;
  analysis::LogHistogram pdf_kinetic_, pdf_elastic_, pdf_total_;
  bool finished_ = false;
};

} // namespace yuxi
