// The energy books of a simulation at one instant: every joule booked (docs/models/fish-basin.md
// section 8).
//
// balance() = mechanical + relaxation + dissipated + removed - wall_work - gravity_work - inserted
// is conserved by the exact dynamics: what moving walls and gravity put in, and what came in
// from outside the equations of motion (inserted), is still mechanical energy, waits in a
// relaxation buffer (thermodynamic model), has been dissipated, or left with grains removed from
// the domain.
//
// Along periodic axes gravity has no potential (a grain that wraps around would jump in height),
// so the gravitational energy counts only the components of g along non-periodic axes, and the
// work of the others (a tilted periodic chute) is booked as gravity_work.
//
// Every total is listed once, in `totals`: summing over ranks, checkpoints and merging saved
// sections go through that list, and energies.csv through `csv_columns` (energy_books.cpp). A
// new total is a field, a line in `totals` and a line in the columns.
#pragma once

#include "domain/comm.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <tuple>

namespace yuxi {

struct EnergyBooks {
  std::int64_t step = 0;
  double time = 0.0;
  double translational = 0.0; // sum m v^2 / 2 over grains [energy]
  double rotational = 0.0;    // sum J w^2 / 2 over grains
  double elastic = 0.0;       // energy stored in contact springs
  double gravitational = 0.0; // sum -m g . x over grains (zero at the origin)
  double relaxation = 0.0;    // energy in contacts' relaxation buffers, on its way to heat
  double dissipated = 0.0;    // cumulative, since the start of the run
  double wall_work = 0.0;     // cumulative work done by moving walls on grains
  double removed = 0.0;       // cumulative mechanical energy of grains removed on escape
  double gravity_work = 0.0;  // cumulative work of gravity along periodic axes
  // Cumulative energy put in from outside the equations of motion: the mechanical energy of
  // grains inserted during the run, and the change of the mechanical energy where a run branches
  // from another's state under a different scene (another contact law, gravity or coefficients).
  double inserted = 0.0;
  std::size_t grains = 0;
  std::size_t contacts = 0;
  std::size_t escaped = 0; // grains removed after leaving the domain

  // The totals: sums over the ranks' parts (step and time are the same on every rank).
  static constexpr auto totals = std::make_tuple(
      &EnergyBooks::translational, &EnergyBooks::rotational, &EnergyBooks::elastic,
      &EnergyBooks::gravitational, &EnergyBooks::relaxation, &EnergyBooks::dissipated,
      &EnergyBooks::wall_work, &EnergyBooks::removed, &EnergyBooks::gravity_work,
      &EnergyBooks::inserted, &EnergyBooks::grains, &EnergyBooks::contacts, &EnergyBooks::escaped);
  static constexpr int n_totals = std::tuple_size_v<decltype(totals)>;
  template <class F> void for_each_total(F&& fn) {
    std::apply([&](auto... member) { (fn(this->*member), ...); }, totals);
  }
  template <class F> void for_each_total(F&& fn) const {
    std::apply([&](auto... member) { (fn(this->*member), ...); }, totals);
  }

  double kinetic() const { return translational + rotational; }
  double mechanical() const { return translational + rotational + elastic + gravitational; }
  double balance() const {
    return mechanical() + relaxation + dissipated + removed - wall_work - gravity_work - inserted;
  }
  // Adds another part's totals to these.
  void add(const EnergyBooks& other);
  // Every total summed over the ranks of `comm`, in one reduction (the counts ride along as
  // doubles, exact below 2^53). Collective.
  void sum_over(const Comm& comm);
  // True when every total is finite.
  bool finite() const;

  // energies.csv: the header line and one row (no newline at the end of either).
  static std::string csv_header();
  std::string csv_row() const;
};

} // namespace yuxi
