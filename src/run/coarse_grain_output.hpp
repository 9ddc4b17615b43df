// The [[coarse_grain]] tables of a run (scene/coarse_grain_spec.hpp): every `interval`, each
// rank adds the coarse-graining sums of its grains and of the contacts it lists, the sums are
// added over the ranks, and rank 0 writes the fields into coarse_grain/<name>/: a CSV and a VTK
// file (an image, .vti, on a Cartesian grid; a structured grid, .vts, on a cylindrical one; for
// ParaView, with a .pvd series) per write (docs/coarse-graining.md, "In a
// run"). With average_every = k, the sums of every k-th step since the last write are averaged:
// the fields of the mean sums (a time average; the ranks add theirs at the write only).
#pragma once

#include "analysis/cg_cylinder.hpp"
#include "analysis/coarse_grain.hpp"
#include "run/coarse_grain_contacts.hpp"
#include "scene/coarse_grain_spec.hpp"
#include "sim/simulation.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace yuxi {

// The parts of the contacts' sums a table needs: those of its fields, none with contacts =
// false (then no contact is recorded for it).
analysis::CgParts contact_parts(const CoarseGrainSpec& spec);

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
    analysis::CgSettings settings;                        // a Cartesian grid's
    std::optional<analysis::CgCylinderSettings> cylinder; // or a cylindrical one
    std::size_t points() const { return cylinder ? cylinder->grid.size() : settings.grid.size(); }
    std::int64_t every = 1;  // steps between writes
    std::int64_t sample = 1; // steps between samples (every, or average_every)
    std::filesystem::path folder;
    std::vector<double> sums; // this rank's, since the last write
    std::int64_t samples = 0;
    std::set<std::int64_t> written; // the steps of the folder's files (rank 0)
    bool listed = false;            // whether the folder was read for them
  };
  static std::string extension(const Table& t); // of its VTK files
  void write(Table& t, const analysis::CgFields& f, std::int64_t step) const;
  std::vector<Table> tables_;
  CoarseGrainInput input_; // the grains and contacts of a sample
  double dt_;
  bool root_;
};

} // namespace yuxi
