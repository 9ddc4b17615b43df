// Continuum fields from grains and contacts by coarse-graining (Goldhirsch, Granular Matter
// 12:239, 2010; Weinhart, Thornton, Luding & Bokhove, Granular Matter 14:289, 2012): the
// definitions, with their equations, are in docs/coarse-graining.md.
//
// Stresses are positive in compression (a pressure is positive), so that the momentum balance
// reads d(rho V)/dt + div(rho V V) = -div(sigma) + rho g + t, with sigma = sigma_k + sigma_c the
// kinetic and contact stresses and t the walls' force density. A tensor T is stored row-major,
// T[3 a + b] = T_ab; for the contact stress T_ab = sum f_a b_b psi, the force's component a and
// the branch's component b.
#pragma once

#include "analysis/cg_function.hpp"
#include "analysis/cg_grid.hpp"
#include "core/vec3.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace yuxi::analysis {

// The grains (never wall particles: their contacts are walls' contacts).
struct CgGrains {
  std::span<const Vec3> x, v;     // positions (any periodic image), velocities
  std::span<const double> mass;   // kg
  std::span<const double> volume; // m^3 (4/3 pi r^3 for a sphere)
};

// One contact, once: grain a with another grain b (b stands at centre - branch: it may be
// another rank's), or grain a with a wall (a plane, mesh, cylinder or wall particle).
struct CgContact {
  Vec3 centre;           // a's centre, m
  double volume = 0.0;   // a's volume, m^3
  bool wall = false;     // with a wall; else with a grain b
  double volume_b = 0.0; // b's volume (its share of the fabric), m^3
  Vec3 force;            // on a, N (on b: -force)
  Vec3 branch;           // to a's centre from b's centre (the image a touches), or from the
                         // contact point on a wall, m
  Vec3 point;            // the contact point, m
  double elastic = 0.0;  // the contact's elastic energy, J
  // a's and b's places among the grains (CgGrains), where known (-1: not among them, such as
  // another rank's grain or an image): a grain's contacts then count in the coordination and
  // fabric with that grain's own weights, one evaluation a grain rather than one a contact.
  std::int64_t grain = -1, grain_b = -1;
  double dissipation = 0.0; // the power it turns to heat: the energy dissipated in a step / dt, W
  double relaxation = 0.0;  // the energy in its relaxation buffer (thermodynamic model), J
  double wall_power = 0.0;  // with a moving wall: the power of its motion on a, f . u_wall, W
};

// The parts of the contacts' sums a caller needs; the sums of a part left out stay zero, and
// its weights are never computed (a table that writes the stress alone skips the contact
// points and the fabric).
struct CgParts {
  bool branches = true;       // the contact stress (a line integral along each branch)
  bool contact_points = true; // wall force and power, elastic, dissipation, relaxation densities
  bool fabric = true;         // coordination and fabric (at the grains' centres)
  bool any() const { return branches || contact_points || fabric; }
};
// The parts that the fields named `names` (as named_fields names them) need.
CgParts parts_for(std::span<const std::string> names);

struct CgSettings {
  CgKind kind = CgKind::gaussian;
  double width = 0.0;  // w, m (bins: unused)
  double cutoff = 0.0; // c, m (bins: unused)
  CgGrid grid;
  CgParts parts;
};

// The fields at every point of the grid (CgGrid::index order); vectors 3 and tensors 9 values a
// point, one point after another.
struct CgFields {
  std::vector<double> density;         // rho = sum m_i phi_i, kg/m^3
  std::vector<double> number_density;  // n = sum phi_i, 1/m^3
  std::vector<double> volume_fraction; // nu = sum V_i phi_i
  std::vector<double> momentum;        // rho V = sum m_i v_i phi_i, kg/(m^2 s)
  std::vector<double> velocity;        // V = momentum / rho (0 where rho = 0), m/s
  std::vector<double> kinetic_stress;  // sum m_i v'_i v'_i phi_i, v' = v_i - V, Pa
  std::vector<double> contact_stress;  // sum over contacts f b psi, Pa
  std::vector<double> stress;          // kinetic + contact, Pa
  std::vector<double> wall_force;      // t = sum over wall contacts f phi(r - c), N/m^3
  std::vector<double> temperature;     // tr(kinetic stress) / (3 rho), m^2/s^2
  std::vector<double> coordination;    // sum z_i phi_i / n: contacts per grain
  std::vector<double> fabric;          // sum V_i phi_i sum_c n_c n_c
  std::vector<double> kinetic_energy;  // sum m_i v_i^2 / 2 phi_i, J/m^3
  std::vector<double> elastic_energy;  // sum over contacts E phi(r - c), J/m^3
  std::vector<double> dissipation;     // sum over contacts P phi(r - c), W/m^3
  std::vector<double> relaxation;      // sum over contacts E_R phi(r - c), J/m^3
  std::vector<double> wall_power;      // sum over wall contacts f . u_w phi(r - c), W/m^3
};

// A field by its name in the files and in Python (scene/coarse_grain_spec.hpp lists the same
// names, in the same order), with its values and their components a point (1, 3 or 9).
struct CgNamedField {
  std::string_view name;
  const std::vector<double>* values;
  int components;
};
// Every field of f, in that order.
std::vector<CgNamedField> named_fields(const CgFields& f);

// Every field is made of sums over grains and contacts; the fields that divide (velocity,
// temperature, coordination) or subtract (the kinetic stress's rho V V) are made from the sums
// at the end. The sums of several parts (the ranks' grains and contacts, each contact on one
// rank) add up to the sums of the whole: reduce them, then make the fields once.
inline constexpr std::size_t cg_sums_per_point = 42;

// The sums at every point (cg_sums_per_point a point). Throws std::invalid_argument for bad
// settings (naming the setting) or inconsistent inputs.
std::vector<double> coarse_grain_sums(const CgGrains& grains, std::span<const CgContact> contacts,
                                      const CgSettings& settings);
// The fields from the (summed) sums on `grid`, or at `points` points.
CgFields coarse_grain_fields(std::span<const double> sums, const CgGrid& grid);
CgFields coarse_grain_fields(std::span<const double> sums, std::size_t points);

// The coarse-grained densities of per-grain quantities: at each point p and for each quantity
// q (a span of one value a grain), sum_i q_i phi(r_p - x_i), the quantity per m^3 (q = 1 gives
// the number density, a grain's energy the energy density). Point after point, quantities.size()
// values a point. Throws std::invalid_argument if a quantity's length is not x's.
std::vector<double> coarse_grain_densities(std::span<const Vec3> x,
                                           std::span<const std::span<const double>> quantities,
                                           const CgSettings& settings);

// Both: the fields of `grains` and `contacts` on settings.grid.
CgFields coarse_grain(const CgGrains& grains, std::span<const CgContact> contacts,
                      const CgSettings& settings);

} // namespace yuxi::analysis
