// The [[coarse_grain]] tables of a run (scene/coarse_grain_spec.hpp): every `interval`, each
// rank adds the coarse-graining sums of its grains and of the contacts it lists, the sums are
// added over the ranks, and rank 0 writes the fields into coarse_grain/<name>/: a CSV and a VTK
// image (.vti, for ParaView, with a .pvd series) per sample (docs/coarse-graining.md, "In a
// run").
#pragma once

#include "analysis/coarse_grain.hpp"
#include "scene/coarse_grain_spec.hpp"
#include "sim/simulation.hpp"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace yuxi {

class CoarseGrainOutput {
public:
  // The tables `specs` of a run with time step dt, written under `dir`.
  CoarseGrainOutput(std::vector<CoarseGrainSpec> specs, const Simulation& sim,
                    std::filesystem::path dir, double dt);

  bool empty() const { return tables_.empty(); }
  // The first step after `step` at which a table samples.
  std::int64_t next_sample_after(std::int64_t step) const;
  // Whether a table samples at `step` with the contacts (they are recorded on that step).
  bool needs_contacts_at(std::int64_t step) const;
  // The tables due at the simulation's step: sums, added over the ranks, written by rank 0.
  // Collective.
  void sample(const Simulation& sim);

private:
  struct Table {
    CoarseGrainSpec spec;
    analysis::CgSettings settings;
    std::int64_t every = 1;
    std::filesystem::path folder;
  };
  void write(const Table& t, const analysis::CgFields& f, std::int64_t step) const;
  std::vector<Table> tables_;
  double dt_;
  bool root_;
};

} // namespace yuxi
