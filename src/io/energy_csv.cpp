#include "io/energy_csv.hpp"

#include <fmt/format.h>
#include <stdexcept>

namespace yuxi {

EnergyCsv::EnergyCsv(const std::filesystem::path& path) : file_(std::fopen(path.c_str(), "w")) {
  if (!file_) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
  fmt::print(file_, "step,time,translational,rotational,elastic,gravitational,mechanical,"
                    "dissipated,wall_work,removed,balance,grains,contacts,escaped\n");
}

EnergyCsv::~EnergyCsv() {
  std::fclose(file_);
}

void EnergyCsv::write(const EnergyReport& e) {
  fmt::print(file_,
             "{},{:.10g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{}"
             ",{},{}\n",
             e.step, e.time, e.translational, e.rotational, e.elastic, e.gravitational,
             e.mechanical(), e.dissipated, e.wall_work, e.removed, e.balance(), e.grains,
             e.contacts, e.escaped);
  if (std::fflush(file_) != 0) throw std::runtime_error("error while writing energies.csv");
}

} // namespace yuxi
