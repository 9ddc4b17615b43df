#include "io/scene_writer.hpp"

#include <sstream>
#include <toml++/toml.h>

namespace yuxi {
namespace {

toml::array vec(const Vec3& v) {
  return toml::array{v.x, v.y, v.z};
}

toml::table linear_pair(const std::string& a, const std::string& b,
                        const LinearSpringDashpot::Coeffs& c) {
  return toml::table{
      {"materials", toml::array{a, b}}, {"k_n", c.k_n},   {"k_t", c.k_t},  {"gamma_n", c.gamma_n},
      {"gamma_t", c.gamma_t},           {"mu_s", c.mu_s}, {"mu_d", c.mu_d}};
}

} // namespace

std::string resolved_scene_toml(const Scene& s) {
  toml::table doc;
  toml::array materials;
  for (const auto& m : s.materials) materials.push_back(m);
  doc.insert("materials", materials);
  doc.insert("run", toml::table{{"name", s.run.name},
                                {"dt", s.sim.dt},
                                {"t_end", s.run.t_end},
                                {"allow_large_dt", s.run.allow_large_dt}});
  doc.insert("output", toml::table{{"energy_interval", s.output.energy_interval},
                                   {"snapshot_interval", s.output.snapshot_interval},
                                   {"vtk", s.output.vtk},
                                   {"lammps_dump", s.output.lammps_dump}});
  const auto& b = s.sim.box.boundary;
  toml::table domain{
      {"lo", vec(s.sim.box.lo)},
      {"hi", vec(s.sim.box.hi)},
      {"boundary", toml::array{std::string(to_string(b[0])), std::string(to_string(b[1])),
                               std::string(to_string(b[2]))}},
      {"gravity", vec(s.sim.gravity)},
      {"skin", s.sim.skin},
      {"on_escape", s.sim.on_escape == EscapePolicy::remove ? "remove" : "stop"},
      {"max_overlap_ratio", s.sim.max_overlap_ratio}};
  if (s.sim.cell_size > 0) domain.insert("cell_size", s.sim.cell_size);
  for (Boundary x : b)
    if (x == Boundary::wall)
      domain.insert_or_assign("wall_material", s.materials[s.sim.box_wall_material]);
  doc.insert("domain", domain);

  toml::array pairs;
  const auto& law = std::get<ContactLaw<LinearSpringDashpot>>(s.law);
  for (std::size_t i = 0; i < s.materials.size(); ++i)
    for (std::size_t j = i; j < s.materials.size(); ++j)
      if (law.coeffs.has(i, j))
        pairs.push_back(linear_pair(s.materials[i], s.materials[j], law.coeffs(i, j)));
  doc.insert("contact", toml::table{{"model", s.contact_model}, {"pair", pairs}});

  if (!s.planes.empty()) {
    toml::array planes;
    for (const auto& p : s.planes)
      planes.push_back(toml::table{{"point", vec(p.point)},
                                   {"normal", vec(p.normal)},
                                   {"material", s.materials[p.material]},
                                   {"amplitude", p.amplitude},
                                   {"omega", p.omega},
                                   {"t0", p.t0}});
    doc.insert("plane", planes);
  }
  if (s.basin) {
    const auto& k = *s.basin;
    doc.insert("basin",
               toml::table{{"cells", toml::array{k.cells[0], k.cells[1], k.cells[2]}},
                           {"spacing", k.spacing},
                           {"radius", k.radius},
                           {"wall_thickness", k.wall_thickness},
                           {"wall_height", k.wall_height},
                           {"bottom_layers", k.bottom_layers},
                           {"fill_layers", k.fill_layers},
                           {"wall_radius", k.wall_radius},
                           {"radius_mean", k.radius_mean},
                           {"radius_sd", k.radius_sd},
                           {"jitter", k.jitter},
                           {"seed", static_cast<std::int64_t>(k.seed)},
                           {"grain_material", s.materials[k.grain_material]},
                           {"wall_material", s.materials[k.wall_material]},
                           {"excitation", toml::table{{"mode", k.excitation.mode},
                                                      {"amplitude", k.excitation.amplitude},
                                                      {"omega", k.excitation.omega},
                                                      {"t0", k.excitation.t0}}}});
  }
  if (!s.particles.empty()) {
    toml::array parts;
    for (const auto& p : s.particles)
      parts.push_back(toml::table{{"position", vec(p.position)},
                                  {"velocity", vec(p.velocity)},
                                  {"angular_velocity", vec(p.angular_velocity)},
                                  {"radius", p.radius},
                                  {"mass", p.mass},
                                  {"material", s.materials[p.material]},
                                  {"kind", p.kind == Kind::wall ? "wall" : "grain"}});
    doc.insert("particle", parts);
  }
  std::ostringstream out;
  out << "# Resolved scene: the input with every default filled in. Runs as it stands.\n"
      << "# Source: " << s.source << "\n\n"
      << doc << "\n";
  return out.str();
}

} // namespace yuxi
