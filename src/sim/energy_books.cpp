#include "sim/energy_books.hpp"

#include <array>
#include <cmath>
#include <fmt/format.h>
#include <type_traits>

namespace yuxi {
namespace {

// The columns of energies.csv after step and time, in file order: energies as %.12g, then
// the counts as integers.
struct EnergyColumn {
  const char* name;
  double (*value)(const EnergyBooks&);
};
constexpr EnergyColumn energy_columns[] = {
    {"translational", [](const EnergyBooks& e) { return e.translational; }},
    {"rotational", [](const EnergyBooks& e) { return e.rotational; }},
    {"elastic", [](const EnergyBooks& e) { return e.elastic; }},
    {"gravitational", [](const EnergyBooks& e) { return e.gravitational; }},
    {"mechanical", [](const EnergyBooks& e) { return e.mechanical(); }},
    {"relaxation", [](const EnergyBooks& e) { return e.relaxation; }},
    {"dissipated", [](const EnergyBooks& e) { return e.dissipated; }},
    {"wall_work", [](const EnergyBooks& e) { return e.wall_work; }},
    {"gravity_work", [](const EnergyBooks& e) { return e.gravity_work; }},
    {"removed", [](const EnergyBooks& e) { return e.removed; }},
    {"inserted", [](const EnergyBooks& e) { return e.inserted; }},
    {"balance", [](const EnergyBooks& e) { return e.balance(); }},
};
struct CountColumn {
  const char* name;
  std::size_t EnergyBooks::*member;
};
constexpr CountColumn count_columns[] = {
    {"grains", &EnergyBooks::grains},
    {"contacts", &EnergyBooks::contacts},
    {"escaped", &EnergyBooks::escaped},
};

} // namespace

void EnergyBooks::add(const EnergyBooks& other) {
  std::apply([&](auto... member) { ((this->*member += other.*member), ...); }, totals);
}

void EnergyBooks::sum_over(const Comm& comm) {
  std::array<double, n_totals> sums{};
  std::size_t k = 0;
  for_each_total([&](const auto& v) { sums[k++] = static_cast<double>(v); });
  comm.sum(sums.data(), n_totals);
  k = 0;
  for_each_total([&](auto& v) {
    if constexpr (std::is_floating_point_v<std::remove_reference_t<decltype(v)>>)
      v = sums[k++];
    else
      v = static_cast<std::remove_reference_t<decltype(v)>>(std::llround(sums[k++]));
  });
}

bool EnergyBooks::finite() const {
  bool ok = std::isfinite(time);
  for_each_total([&](const auto& v) { ok = ok && std::isfinite(static_cast<double>(v)); });
  return ok;
}

std::string EnergyBooks::csv_header() {
  std::string out = "step,time";
  for (const auto& c : energy_columns) out += fmt::format(",{}", c.name);
  for (const auto& c : count_columns) out += fmt::format(",{}", c.name);
  return out;
}

std::string EnergyBooks::csv_row() const {
  std::string out = fmt::format("{},{:.10g}", step, time);
  for (const auto& c : energy_columns) out += fmt::format(",{:.12g}", c.value(*this));
  for (const auto& c : count_columns) out += fmt::format(",{}", this->*c.member);
  return out;
}

} // namespace yuxi
