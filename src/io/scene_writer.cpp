#include "io/scene_writer.hpp"

#include "contact/contact_model.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>
#include <toml++/toml.h>
#include <type_traits>

namespace yuxi {
namespace {

toml::array vec(const Vec3& v) {
  return toml::array{v.x, v.y, v.z};
}

// The drift and the oscillation of a rigid motion, and its times, as keys of a wall's table.
void write_carrying(const RigidMotion& r, toml::table& t) {
  t.insert("velocity", vec(r.drift));
  if (r.amplitude != 0.0) {
    t.insert("oscillate_amplitude", r.amplitude);
    t.insert("oscillate_direction", vec(r.direction));
    t.insert("oscillate_omega", r.frequency);
  }
  t.insert("t0", r.t0);
  if (std::isfinite(r.t1)) t.insert("t1", r.t1);
}

// The motion of a mesh as the keys of its [[mesh]] table.
void write_motion(const WallMotion& motion, toml::table& t) {
  if (const auto* r = std::get_if<RigidMotion>(&motion)) {
    t.insert("omega", r->omega);
    t.insert("axis", vec(r->axis));
    t.insert("axis_point", vec(r->center));
    write_carrying(*r, t);
  } else if (const auto* m = std::get_if<RadialCosineMotion>(&motion)) {
    t.insert("radial_mode", m->mode);
    t.insert("radial_amplitude", m->amplitude);
    t.insert("radial_omega", m->omega);
    t.insert("radial_center", vec(m->center));
    t.insert("t0", m->t0);
  }
}

toml::table region_table(const Region& region) {
  toml::table t;
  std::visit(
      [&](const auto& r) {
        using R = std::decay_t<decltype(r)>;
        if constexpr (std::is_same_v<R, BoxRegion>) {
          t.insert("shape", "box");
          t.insert("lo", vec(r.lo));
          t.insert("hi", vec(r.hi));
        } else if constexpr (std::is_same_v<R, CylinderRegion>) {
          t.insert("shape", "cylinder");
          t.insert("center", vec(r.center));
          t.insert("axis", vec(r.axis));
          t.insert("radius", r.radius);
          t.insert("lo", r.lo);
          t.insert("hi", r.hi);
        } else if constexpr (std::is_same_v<R, SphereRegion>) {
          t.insert("shape", "sphere");
          t.insert("center", vec(r.center));
          t.insert("radius", r.radius);
        } else if constexpr (std::is_same_v<R, MeshRegion>) {
          t.insert("shape", "mesh");
          t.insert("file", r.file());
          t.insert("scale", r.scale);
          t.insert("rotate_axis", vec(r.rotate_axis));
          t.insert("rotate_degrees", r.rotate_degrees);
          t.insert("translate", vec(r.translate));
        } else {
          t.insert("shape", "half_space");
          t.insert("point", vec(r.point));
          t.insert("normal", vec(r.normal));
        }
      },
      region.shape());
  return t;
}

// The keys of a [[fill]] or [[insert]] table that describe its grains.
void write_grains(const Scene& s, const GrainKind& g, toml::table& t) {
  using Kind = SizeDistribution::Kind;
  const SizeDistribution& d = g.size;
  toml::table size;
  switch (d.kind) {
  case Kind::constant:
    size.insert("distribution", "constant");
    size.insert("radius", d.radius);
    break;
  case Kind::uniform:
    size.insert("distribution", "uniform");
    break;
  case Kind::normal:
  case Kind::lognormal:
    size.insert("distribution", d.kind == Kind::normal ? "normal" : "lognormal");
    size.insert("mean", d.mean);
    size.insert("sd", d.sd);
    break;
  case Kind::discrete: {
    size.insert("distribution", "discrete");
    toml::array radii, weights;
    for (double r : d.radii) radii.push_back(r);
    for (double w : d.weights) weights.push_back(w);
    size.insert("radii", radii);
    size.insert("weights", weights);
    size.insert("weights_by", d.by_mass ? "mass" : "number");
    break;
  }
  }
  if (d.kind == Kind::uniform || d.kind == Kind::normal || d.kind == Kind::lognormal) {
    size.insert("min", d.min);
    size.insert("max", d.max);
  }
  t.insert("size", size);
  t.insert("material", s.materials[g.material]);
  t.insert("density", g.density);
  t.insert("velocity", vec(g.velocity));
  t.insert("velocity_spread", g.velocity_spread);
  t.insert("seed", static_cast<std::int64_t>(g.seed));
}

void write_sources(const Scene& s, toml::table& doc) {
  if (!s.shapes.empty()) {
    toml::array shapes;
    for (std::size_t k = 0; k < s.shapes.size(); ++k) {
      toml::array spheres;
      for (const SphereMember& m : s.shape_spheres[k])
        spheres.push_back(toml::array{m.centre.x, m.centre.y, m.centre.z, m.radius});
      shapes.push_back(toml::table{{"name", s.shapes[k].name}, {"spheres", spheres}});
    }
    doc.insert("shape", shapes);
  }
  if (!s.clumps.empty()) {
    toml::array clumps;
    for (const ClumpSpec& c : s.clumps) {
      const Quaternion& q = c.orientation;
      clumps.push_back(toml::table{{"shape", s.shapes[static_cast<std::size_t>(c.shape)].name},
                                   {"position", vec(c.position)},
                                   {"orientation", toml::array{q.w, q.x, q.y, q.z}},
                                   {"velocity", vec(c.velocity)},
                                   {"angular_velocity", vec(c.angular_velocity)},
                                   {"scale", c.scale},
                                   {"material", s.materials[c.material]},
                                   {"density", c.density}});
    }
    doc.insert("clump", clumps);
  }
  if (!s.fills.empty()) {
    toml::array fills;
    for (const FillSpec& f : s.fills) {
      toml::table t{{"region", region_table(f.region)}};
      write_grains(s, f.grains, t);
      if (f.shape >= 0) t.insert("shape", s.shapes[static_cast<std::size_t>(f.shape)].name);
      if (f.walls) {
        t.insert("kind", "wall");
        t.erase("velocity");
        t.erase("velocity_spread");
      }
      switch (f.amount) {
      case FillSpec::Amount::count:
        t.insert("count", static_cast<std::int64_t>(std::llround(f.value)));
        break;
      case FillSpec::Amount::packing_fraction:
        t.insert("packing_fraction", f.value);
        break;
      case FillSpec::Amount::mass:
        t.insert("mass", f.value);
        break;
      }
      const bool lattice = f.placement == FillSpec::Placement::lattice;
      t.insert("placement", lattice ? "lattice" : "random");
      if (lattice) t.insert("jitter", f.jitter);
      if (!lattice) t.insert("attempts", f.attempts_per_grain);
      fills.push_back(t);
    }
    doc.insert("fill", fills);
  }
  if (!s.inserts.empty()) {
    toml::array inserts;
    for (const InsertSpec& i : s.inserts) {
      toml::table t{{"name", i.name}, {"region", region_table(i.region)}};
      write_grains(s, i.grains, t);
      t.insert(i.by_mass ? "mass_rate" : "rate", i.rate);
      t.insert("start", i.start);
      if (std::isfinite(i.end)) t.insert("end", i.end);
      if (i.total >= 0) t.insert("total", i.total);
      t.insert("interval", i.interval);
      t.insert("attempts", i.attempts);
      if (i.held) t.insert("held", true);
      if (i.shape >= 0) t.insert("shape", s.shapes[static_cast<std::size_t>(i.shape)].name);
      inserts.push_back(t);
    }
    doc.insert("insert", inserts);
  }
  if (!s.outlets.empty()) {
    toml::array outlets;
    for (const OutletSpec& o : s.outlets)
      outlets.push_back(toml::table{{"name", o.name}, {"region", region_table(o.region)}});
    doc.insert("outlet", outlets);
  }
}

void write_coarse_grains(const Scene& s, toml::table& doc) {
  if (s.coarse_grains.empty()) return;
  toml::array tables;
  for (const CoarseGrainSpec& c : s.coarse_grains) {
    toml::table t;
    t.insert("name", c.name);
    t.insert("function", c.function);
    if (c.function != "bins") {
      t.insert("width", c.width);
      t.insert("cutoff", c.cutoff);
    }
    std::string average;
    if (c.cylindrical) {
      t.insert("axis", toml::array{c.axis_x, c.axis_y});
      t.insert("lo", toml::array{c.lo.x, c.lo.z});
      t.insert("hi", toml::array{c.hi.x, c.hi.z});
      if (c.averaged[1]) average = "theta";
      if (c.averaged[2]) average += average.empty() ? "z" : " z";
    } else {
      t.insert("lo", vec(c.lo));
      t.insert("hi", vec(c.hi));
      for (int a = 0; a < 3; ++a)
        if (c.averaged[static_cast<std::size_t>(a)]) average += static_cast<char>('x' + a);
    }
    t.insert("n", toml::array{c.n[0], c.n[1], c.n[2]});
    t.insert("average", average);
    t.insert("interval", c.interval);
    if (c.average_every > 0) t.insert("average_every", c.average_every);
    t.insert("contacts", c.contacts);
    toml::array fields;
    for (const std::string& f : c.fields) fields.push_back(f);
    t.insert("fields", fields);
    tables.push_back(t);
  }
  doc.insert("coarse_grain", tables);
}

void write_measures(const Scene& s, toml::table& doc) {
  if (s.measures.empty()) return;
  using Quantity = MeasureSpec::Quantity;
  toml::array measures;
  for (const MeasureSpec& m : s.measures) {
    static constexpr const char* names[] = {"mass",           "grains", "kinetic_per_grain",
                                            "surface_height", "angle",  "wall_force"};
    toml::table t{{"name", m.name}, {"quantity", names[static_cast<int>(m.quantity)]}};
    if (m.region) t.insert("region", region_table(*m.region));
    if (m.bin > 0) t.insert("bin", m.bin);
    if (m.quantity == Quantity::wall_force) t.insert("wall", m.wall);
    if (m.quantity == Quantity::angle) {
      if (m.about_axis) {
        t.insert("axis_point", vec(m.point));
      } else {
        t.insert("point", vec(m.point));
        t.insert("direction", vec(m.direction));
      }
      if (std::isfinite(m.from)) t.insert("from", m.from);
      if (std::isfinite(m.to)) t.insert("to", m.to);
    }
    measures.push_back(t);
  }
  doc.insert("measure", measures);
}

void write_window(const ActiveWindow& w, toml::table& t) {
  if (std::isfinite(w.from)) t.insert("active_from", w.from);
  if (std::isfinite(w.until)) t.insert("active_until", w.until);
}

// Writes one model's pair keys (ModelScene<Model>::fields, scene_fields.hpp) into a table.
struct FieldWriter {
  toml::table& t;
  void required(std::string_view k, double& x) { t.insert(k, x); }
  void optional(std::string_view k, double& x) { t.insert(k, x); }
  void optional_or(std::string_view k, double& x, double) { t.insert(k, x); }
  void fraction(std::string_view k, double& x) { t.insert(k, x); }
  template <class E>
  void choice(std::string_view k, E& x,
              std::initializer_list<std::pair<std::string_view, E>> options) {
    for (const auto& [name, value] : options)
      if (value == x) t.insert(k, std::string(name));
  }
  void check(bool, std::string_view, const std::string&) {}
};

void write_shaped_walls(const Scene& s, toml::table& doc) {
  toml::array meshes, cylinders;
  for (const ShapedWall& wall : s.walls) {
    if (const auto* m = std::get_if<MeshWall>(&wall)) {
      toml::table t{{"name", m->name},
                    {"file", m->file},
                    {"material", s.materials[m->material]},
                    {"scale", m->scale},
                    {"rotate_axis", vec(m->rotate_axis)},
                    {"rotate_degrees", m->rotate_degrees},
                    {"translate", vec(m->translate)},
                    {"surface_velocity", vec(m->surface_velocity)},
                    {"merge_degrees", m->merge_degrees},
                    {"torque_point", vec(m->torque_point)}};
      write_motion(m->motion, t);
      write_window(m->active, t);
      if (const auto* servo = dynamic_cast<const ForceServo*>(m->controller.get())) {
        t.insert("servo_axis", vec(m->servo_axis));
        t.insert("servo_force", servo->target());
        t.insert("servo_gain", servo->gain());
        t.insert("servo_max_speed", servo->max_speed());
      } else if (m->controller) {
        t.insert("servo_axis", vec(m->servo_axis));
        t.insert("controlled", true);
      }
      meshes.push_back(t);
    } else {
      const auto& c = std::get<CylinderWall>(wall);
      toml::table t{{"name", c.name},
                    {"center", vec(c.center)},
                    {"axis", vec(c.axis)},
                    {"radius", c.radius},
                    {"grains", c.inside ? "inside" : "outside"},
                    {"ends", c.capped ? "capped" : "open"},
                    {"omega", c.omega},
                    {"material", s.materials[c.material]}};
      if (std::isfinite(c.lo)) t.insert("lo", c.lo);
      if (std::isfinite(c.hi)) t.insert("hi", c.hi);
      if (c.moves()) write_carrying(c.carried, t);
      write_window(c.active, t);
      cylinders.push_back(t);
    }
  }
  if (!meshes.empty()) doc.insert("mesh", meshes);
  if (!cylinders.empty()) doc.insert("cylinder", cylinders);
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
                                {"allow_large_dt", s.run.allow_large_dt},
                                {"device", run_device_name(s.run.device)}});
  doc.insert("output", toml::table{{"energy_interval", s.output.energy_interval},
                                   {"snapshot_interval", s.output.snapshot_interval},
                                   {"vtk", s.output.vtk},
                                   {"lammps_dump", s.output.lammps_dump}});
  doc.insert("checkpoint", toml::table{{"every_steps", s.checkpoint.every_steps},
                                       {"every_minutes", s.checkpoint.every_minutes},
                                       {"keep", s.checkpoint.keep}});
  const auto& b = s.sim.box.boundary;
  toml::table domain{
      {"lo", vec(s.sim.box.lo)},
      {"hi", vec(s.sim.box.hi)},
      {"boundary", toml::array{std::string(to_string(b[0])), std::string(to_string(b[1])),
                               std::string(to_string(b[2]))}},
      {"gravity", vec(s.sim.gravity)},
      {"skin", s.sim.skin},
      {"on_escape", s.sim.on_escape == EscapePolicy::remove ? "remove" : "stop"},
      {"max_overlap_ratio", s.sim.max_overlap_ratio},
      {"ranks", toml::array{s.sim.ranks[0], s.sim.ranks[1], s.sim.ranks[2]}},
      {"rebalance_every", s.sim.rebalance_every},
      {"balance_by", s.sim.balance_by == BalanceBy::time ? "time" : "pairs"}};
  if (s.sim.cell_size > 0) domain.insert("cell_size", s.sim.cell_size);
  for (Boundary x : b)
    if (x == Boundary::wall)
      domain.insert_or_assign("wall_material", s.materials[s.sim.box_wall_material]);
  doc.insert("domain", domain);

  toml::array pairs;
  std::visit(
      [&](const auto& law) {
        using Model = typename std::decay_t<decltype(law)>::model_type;
        for (std::size_t i = 0; i < s.materials.size(); ++i)
          for (std::size_t j = i; j < s.materials.size(); ++j) {
            if (!law.coeffs.has(i, j)) continue;
            toml::table pair{{"materials", toml::array{s.materials[i], s.materials[j]}}};
            auto coeffs = law.coeffs(i, j);
            FieldWriter writer{pair};
            ModelScene<Model>::fields(writer, coeffs);
            pairs.push_back(pair);
          }
      },
      s.law);
  doc.insert(
      "contact",
      toml::table{{"model", s.contact_model}, {"preset", s.contact_preset}, {"pair", pairs}});
  toml::table props;
  for (std::size_t k = 0; k < s.materials.size(); ++k) {
    const auto& p = s.material_properties[k];
    toml::table m;
    if (!std::isnan(p.youngs_modulus)) m.insert("youngs_modulus", p.youngs_modulus);
    if (!std::isnan(p.poisson_ratio)) m.insert("poisson_ratio", p.poisson_ratio);
    if (!std::isnan(p.density)) m.insert("density", p.density);
    if (!m.empty()) props.insert(s.materials[k], m);
  }
  if (!props.empty()) doc.insert("material", props);

  if (!s.planes.empty()) {
    toml::array planes;
    for (const auto& p : s.planes)
      planes.push_back(toml::table{{"name", p.name},
                                   {"point", vec(p.point)},
                                   {"normal", vec(p.normal)},
                                   {"material", s.materials[p.material]},
                                   {"amplitude", p.amplitude},
                                   {"omega", p.omega},
                                   {"t0", p.t0}});
    doc.insert("plane", planes);
  }
  write_shaped_walls(s, doc);
  if (s.basin) {
    const auto& k = *s.basin;
    doc.insert("basin",
               toml::table{{"cells", toml::array{k.cells[0], k.cells[1], k.cells[2]}},
                           {"spacing", k.spacing},
                           {"radius", k.radius},
                           {"wall_thickness", k.wall_thickness},
                           {"wall_height", k.wall_height},
                           {"side_wall", k.side_particles ? "particles" : "none"},
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
  if (s.analysis) {
    const auto& a = *s.analysis;
    const auto list = [](const std::vector<double>& v) {
      toml::array out;
      for (double x : v) out.push_back(x);
      return out;
    };
    doc.insert("analysis", toml::table{{"grid", toml::array{a.grid[0], a.grid[1]}},
                                       {"surface_times", list(a.surface_times)},
                                       {"velocity_times", list(a.velocity_times)},
                                       {"section_half_thickness", a.section_half_thickness},
                                       {"section_azimuth", a.section_azimuth},
                                       {"elastic_map_times", list(a.elastic_map_times)},
                                       {"period_start", a.period_start},
                                       {"period_length", a.period_length},
                                       {"sample_interval", a.sample_interval},
                                       {"section_heights", list(a.section_heights)},
                                       {"section_width", a.section_width},
                                       {"pdf_range", toml::array{a.pdf_range[0], a.pdf_range[1]}},
                                       {"bins_per_decade", a.bins_per_decade},
                                       {"fit_a", toml::array{a.fit_a[0], a.fit_a[1]}},
                                       {"fit_b", toml::array{a.fit_b[0], a.fit_b[1]}},
                                       {"mode", a.mode},
                                       {"r_max", a.r_max},
                                       {"sector_half_width", a.sector_half_width},
                                       {"profile_bin", a.profile_bin},
                                       {"track_interval", a.track_interval},
                                       {"track_until", a.track_until},
                                       {"wave_interval", a.wave_interval},
                                       {"wave_until", a.wave_until},
                                       {"grain_sample_interval", a.grain_sample_interval},
                                       {"grain_samples_from", a.grain_samples_from},
                                       {"grain_samples_until", a.grain_samples_until}});
  }
  if (s.lammps_data) {
    toml::array types, frozen;
    for (auto m : s.lammps_data->type_material) types.push_back(s.materials[m]);
    for (auto t : s.lammps_data->frozen_types) frozen.push_back(t);
    doc.insert("lammps_data",
               toml::table{{"file", std::filesystem::absolute(s.lammps_data->file).string()},
                           {"type_materials", types},
                           {"frozen_types", frozen}});
  }
  if (s.particles.size() > s.n_lammps_atoms) {
    toml::array parts;
    for (std::size_t k = s.n_lammps_atoms; k < s.particles.size(); ++k) {
      const auto& p = s.particles[k];
      parts.push_back(toml::table{{"position", vec(p.position)},
                                  {"velocity", vec(p.velocity)},
                                  {"angular_velocity", vec(p.angular_velocity)},
                                  {"radius", p.radius},
                                  {"mass", p.mass},
                                  {"material", s.materials[p.material]},
                                  {"kind", p.kind == Kind::wall ? "wall" : "grain"}});
    }
    doc.insert("particle", parts);
  }
  write_sources(s, doc);
  write_measures(s, doc);
  write_coarse_grains(s, doc);
  std::ostringstream out;
  out << "# Resolved scene: the input with every default filled in. Runs as it stands.\n\n"
      << doc << "\n";
  return out.str();
}

} // namespace yuxi
