#include "io/scene_reader.hpp"

#include "contact/contact_model.hpp"
#include "core/units.hpp"
#include "io/coarse_grain_scene_reader.hpp"
#include "io/lammps_data_reader.hpp"
#include "io/measure_scene_reader.hpp"
#include "io/shape_scene_reader.hpp"
#include "io/source_scene_reader.hpp"
#include "io/toml_reader.hpp"
#include "io/wall_scene_reader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string_view>
#include <type_traits>
#include <vector>

namespace yuxi {

std::uint8_t material_of(const Scene& scene, TomlReader& t, std::string_view key) {
  const std::string name = t.string(key);
  const auto k = scene.material_index(name);
  if (!k)
    t.fail(key, fmt::format("material \"{}\" is not in the top-level 'materials' list", name));
  return *k;
}

const char* run_device_name(RunDevice device) {
  switch (device) {
  case RunDevice::gpu:
    return "gpu";
  case RunDevice::host:
    return "host";
  case RunDevice::cpu:
    break;
  }
  return "cpu";
}

std::optional<RunDevice> run_device_named(std::string_view name) {
  for (const RunDevice d : {RunDevice::cpu, RunDevice::gpu, RunDevice::host})
    if (name == run_device_name(d)) return d;
  return std::nullopt;
}

namespace {

Boundary to_boundary(const std::string& s) {
  return s == "periodic" ? Boundary::periodic : s == "wall" ? Boundary::wall : Boundary::open;
}

void read_run(Scene& scene, TomlReader& root) {
  auto run = root.table("run");
  if (!run) root.fail("", "missing table [run]");
  scene.run.name = run->string("name", scene.run.name);
  scene.sim.dt = run->positive("dt");
  scene.dt_location = run->where("dt");
  scene.run.t_end = run->positive("t_end");
  scene.run.allow_large_dt = run->boolean("allow_large_dt", false);
  scene.run.device = *run_device_named(run->choice("device", {"cpu", "gpu", "host"}, "cpu"));
  run->finish();
}

void read_output(Scene& scene, TomlReader& root) {
  auto out = root.table("output");
  if (!out) return;
  auto& o = scene.output;
  o.energy_interval = out->positive("energy_interval", o.energy_interval);
  o.snapshot_interval = out->non_negative("snapshot_interval", o.snapshot_interval);
  o.vtk = out->boolean("vtk", o.vtk);
  o.lammps_dump = out->boolean("lammps_dump", o.lammps_dump);
  out->finish();
}

void read_checkpoint_settings(Scene& scene, TomlReader& root) {
  auto c = root.table("checkpoint");
  if (!c) return;
  auto& k = scene.checkpoint;
  k.every_steps =
      c->integer("every_steps", k.every_steps, 0, std::numeric_limits<std::int64_t>::max());
  k.every_minutes = c->non_negative("every_minutes", k.every_minutes);
  k.keep = static_cast<int>(c->integer("keep", k.keep, 1, 1000));
  c->finish();
}

// A pair [lo, hi] with lo < hi (and lo > 0 if positive).
std::array<double, 2> read_range(TomlReader& t, std::string_view key, std::array<double, 2> value,
                                 bool positive) {
  if (!t.has(key)) return value;
  const auto v = t.numbers(key);
  if (v.size() != 2 || !(v[0] < v[1]) || (positive && !(v[0] > 0)))
    t.fail(key, positive ? "expected [lo, hi] with 0 < lo < hi" : "expected [lo, hi] with lo < hi");
  return {v[0], v[1]};
}

// The analyses by sector of the excitation mode (peaks, profiles) and the per-grain samples.
void read_sector_analyses(const Scene& scene, TomlReader& a, AnalysisSettings& s) {
  const Box& box = scene.sim.box;
  if (scene.basin) {
    s.mode = std::max(1, scene.basin->excitation.mode);
    s.r_max = scene.basin->radius * scene.basin->spacing;
  } else {
    s.r_max = 0.5 * box.length(0);
  }
  s.mode = static_cast<int>(a.integer("mode", s.mode, 1, 1000));
  s.r_max = a.positive("r_max", s.r_max);
  s.sector_half_width = a.positive("sector_half_width", 45.0 / s.mode);
  if (s.sector_half_width > 90.0 / s.mode)
    a.fail("sector_half_width",
           fmt::format("{} degrees: at most 90 / m = {} (the wedges of neighbouring antinodes "
                       "would overlap)",
                       s.sector_half_width, 90.0 / s.mode));
  s.profile_bin = a.positive("profile_bin", box.length(0) / s.grid[0]);
  const auto interval = [&](std::string_view key) { return a.non_negative(key, 0.0); };
  s.track_interval = interval("track_interval");
  s.track_until = a.number("track_until", -1.0);
  s.wave_interval = interval("wave_interval");
  s.wave_until = a.number("wave_until", s.period_start + 8.0 * s.period_length);
  s.grain_sample_interval = interval("grain_sample_interval");
  s.grain_samples_from = a.number("grain_samples_from", s.period_start);
  s.grain_samples_until = a.number("grain_samples_until", s.period_start + s.period_length);
  if (s.grain_sample_interval > 0 && !(s.grain_samples_until >= s.grain_samples_from))
    a.fail("grain_samples_until", "must not come before grain_samples_from");
}

void read_analysis(Scene& scene, TomlReader& root) {
  auto a = root.table("analysis");
  if (!a) return;
  AnalysisSettings s;
  const auto grid = a->has("grid") ? a->integers("grid") : std::vector<std::int64_t>{48, 48};
  if (grid.size() != 2 || grid[0] < 1 || grid[1] < 1 || grid[0] > 4096 || grid[1] > 4096)
    a->fail("grid", "expected [nx, ny], each in 1..4096");
  s.grid = {static_cast<int>(grid[0]), static_cast<int>(grid[1])};
  const auto times = [&](std::string_view key) {
    if (!a->has(key)) return std::vector<double>{};
    auto v = a->numbers(key);
    for (double t : v)
      if (t < 0) a->fail(key, "times must not be negative");
    std::sort(v.begin(), v.end());
    return v;
  };
  s.surface_times = times("surface_times");
  s.velocity_times = times("velocity_times");
  s.elastic_map_times = times("elastic_map_times");
  s.section_half_thickness = a->positive("section_half_thickness", s.section_half_thickness);
  s.section_azimuth = a->number("section_azimuth", s.section_azimuth);
  s.period_start = a->number("period_start", s.period_start);
  s.period_length = a->number("period_length", s.period_length);
  if (scene.basin && scene.basin->excitation.omega > 0) { // default: the first period after t0
    if (s.period_start < 0) s.period_start = scene.basin->excitation.t0;
    if (s.period_length <= 0) s.period_length = 2 * pi / scene.basin->excitation.omega;
  }
  if (s.period_start < 0 || s.period_length <= 0)
    a->fail("period_start", "give period_start >= 0 and period_length > 0 (the scene has no "
                            "excited [basin] to take them from)");
  s.sample_interval = a->positive("sample_interval", s.sample_interval);
  if (a->has("section_heights")) {
    s.section_heights = a->numbers("section_heights");
    if (s.section_heights.size() % 2 != 0)
      a->fail("section_heights", "expected pairs z0, z1 (an even count of numbers)");
    for (std::size_t k = 0; k < s.section_heights.size(); k += 2)
      if (!(s.section_heights[k] < s.section_heights[k + 1]))
        a->fail("section_heights", "each slab needs z0 < z1");
  }
  s.section_width = a->non_negative("section_width", s.section_width);
  s.pdf_range = read_range(*a, "pdf_range", s.pdf_range, true);
  s.bins_per_decade = static_cast<int>(a->integer("bins_per_decade", s.bins_per_decade, 1, 1000));
  s.fit_a = read_range(*a, "fit_a", s.fit_a, true);
  s.fit_b = read_range(*a, "fit_b", s.fit_b, true);
  read_sector_analyses(scene, *a, s);
  a->finish();
  scene.analysis = s;
}

void read_domain(Scene& scene, TomlReader& root) {
  auto d = root.table("domain");
  if (!d) root.fail("", "missing table [domain]");
  auto& c = scene.sim;
  c.box.lo = d->vec3("lo");
  c.box.hi = d->vec3("hi");
  for (int a = 0; a < 3; ++a)
    if (!(c.box.hi[a] > c.box.lo[a]))
      d->fail("hi", fmt::format("must exceed 'lo' on every axis (axis {}: {} <= {})", "xyz"[a],
                                c.box.hi[a], c.box.lo[a]));
  if (d->has("boundary")) {
    const auto b = d->strings("boundary");
    if (b.size() != 3) d->fail("boundary", "expected 3 entries (x, y, z)");
    for (int a = 0; a < 3; ++a) {
      if (b[a] != "periodic" && b[a] != "wall" && b[a] != "open")
        d->fail("boundary",
                fmt::format("unknown boundary \"{}\" (expected periodic, wall or open)", b[a]));
      c.box.boundary[a] = to_boundary(b[a]);
    }
  }
  c.gravity = d->vec3("gravity");
  c.cell_size = d->positive("cell_size", 0.0);
  // Without a skin key, the skin is a fraction of the largest grain diameter, taken once the
  // grains are known (check_consistency).
  c.skin = d->has("skin") ? d->non_negative("skin", c.skin) : -1.0;
  c.on_escape = d->choice("on_escape", {"stop", "remove"}, "stop") == "remove"
                    ? EscapePolicy::remove
                    : EscapePolicy::stop;
  c.max_overlap_ratio = d->positive("max_overlap_ratio", c.max_overlap_ratio);
  if (d->has("ranks")) {
    const auto r = d->int3("ranks", 0);
    for (int a = 0; a < 3; ++a) c.ranks[a] = static_cast<int>(r[a]);
  }
  c.rebalance_every =
      static_cast<int>(d->integer("rebalance_every", c.rebalance_every, 0, 1 << 30));
  c.balance_by = d->choice("balance_by", {"pairs", "time"}, "pairs") == "time" ? BalanceBy::time
                                                                               : BalanceBy::pairs;
  const bool has_wall_faces = std::any_of(c.box.boundary.begin(), c.box.boundary.end(),
                                          [](Boundary b) { return b == Boundary::wall; });
  if (has_wall_faces) c.box_wall_material = material_of(scene, *d, "wall_material");
  d->finish();
}

void read_materials(Scene& scene, TomlReader& root) {
  scene.materials = root.strings("materials");
  if (scene.materials.empty()) root.fail("materials", "needs at least one material");
  if (scene.materials.size() > 255) root.fail("materials", "at most 255 materials");
  for (std::size_t a = 0; a < scene.materials.size(); ++a)
    for (std::size_t b = a + 1; b < scene.materials.size(); ++b)
      if (scene.materials[a] == scene.materials[b])
        root.fail("materials", fmt::format("\"{}\" is listed twice", scene.materials[a]));
  scene.material_properties.assign(scene.materials.size(), MaterialProperties{});
  // Optional [material.<name>] tables with elastic properties.
  auto props = root.table("material");
  if (!props) return;
  for (std::size_t k = 0; k < scene.materials.size(); ++k) {
    auto m = props->table(scene.materials[k]);
    if (!m) continue;
    auto& p = scene.material_properties[k];
    if (m->has("youngs_modulus")) p.youngs_modulus = m->positive_or_infinite("youngs_modulus");
    if (m->has("poisson_ratio")) {
      p.poisson_ratio = m->number("poisson_ratio");
      if (!(p.poisson_ratio > -1.0 && p.poisson_ratio < 0.5))
        m->fail("poisson_ratio", fmt::format("must be in (-1, 0.5) (got {})", p.poisson_ratio));
    }
    if (m->has("density")) p.density = m->positive("density");
    m->finish();
  }
  props->finish();
}

// Reads one model's pair keys (ModelScene<Model>::fields, scene_fields.hpp) from a [[contact.pair]]
// table.
struct FieldReader {
  TomlReader& t;
  void required(std::string_view k, double& x) { x = t.positive(k); }
  void optional(std::string_view k, double& x) { x = t.non_negative(k, x); }
  void optional_or(std::string_view k, double& x, double fallback) {
    x = t.non_negative(k, fallback);
  }
  void fraction(std::string_view k, double& x) {
    x = t.number(k, x);
    if (!(x > 0.0 && x <= 1.0)) t.fail(k, fmt::format("must be in (0, 1] (got {})", x));
  }
  template <class E>
  void choice(std::string_view k, E& x,
              std::initializer_list<std::pair<std::string_view, E>> options) {
    if (!t.has(k)) return;
    const std::string name = t.string(k);
    std::vector<std::string_view> names;
    for (const auto& [n, value] : options) {
      if (n == name) {
        x = value;
        return;
      }
      names.push_back(n);
    }
    t.fail(k,
           fmt::format("unknown value \"{}\" (expected one of: {})", name, fmt::join(names, ", ")));
  }
  void check(bool ok, std::string_view k, const std::string& message) {
    if (!ok) t.fail(k, message);
  }
};

// A model whose coefficients also depend on the materials' elastic constants.
template <class M>
concept UsesElasticMaterials = requires(const typename M::Coeffs& c) {
  { ModelScene<M>::with_materials(c, 1.0, 0.3, 1.0, 0.3) } -> std::same_as<typename M::Coeffs>;
};

// A model that takes the scene's preset = "lammps".
template <class M>
concept HasLammpsPreset = requires(typename M::Coeffs& c) {
  ModelScene<M>::lammps_preset(c);
};

// The names of the models that take preset = "lammps", joined by "or".
std::string models_with_lammps_preset() {
  std::vector<std::string_view> names;
  ContactModels::for_each([&]<class M>(std::type_identity<M>) {
    if constexpr (HasLammpsPreset<M>) names.push_back(M::name);
  });
  return fmt::format("{}", fmt::join(names, " or "));
}

// Coefficients of model M for the pair (a, b) from its table.
template <class M>
typename M::Coeffs read_pair(const Scene& scene, TomlReader& p, std::uint8_t a, std::uint8_t b) {
  typename M::Coeffs c{};
  if constexpr (HasLammpsPreset<M>)
    if (scene.contact_preset == "lammps") ModelScene<M>::lammps_preset(c);
  FieldReader reader{p};
  ModelScene<M>::fields(reader, c);
  if constexpr (UsesElasticMaterials<M>) {
    for (std::uint8_t k : {a, b}) {
      const auto& m = scene.material_properties[k];
      if (std::isnan(m.youngs_modulus) || std::isnan(m.poisson_ratio))
        p.fail("materials", fmt::format("{} needs youngs_modulus and poisson_ratio in "
                                        "[material.{}]",
                                        M::name, scene.materials[k]));
    }
    const auto& ma = scene.material_properties[a];
    const auto& mb = scene.material_properties[b];
    if (std::isinf(ma.youngs_modulus) && std::isinf(mb.youngs_modulus))
      p.fail("materials", "both materials are rigid (youngs_modulus = inf)");
    c = ModelScene<M>::with_materials(c, ma.youngs_modulus, ma.poisson_ratio, mb.youngs_modulus,
                                      mb.poisson_ratio);
  }
  return c;
}

// Whether the model of `law` takes preset = "lammps".
bool takes_lammps_preset(const AnyContactLaw& law) {
  return std::visit(
      [](const auto& l) { return HasLammpsPreset<typename std::decay_t<decltype(l)>::model_type>; },
      law);
}

void read_contact(Scene& scene, TomlReader& root) {
  auto c = root.table("contact");
  if (!c) root.fail("", "missing table [contact]");
  scene.contact_model = c->choice("model", contact_model_names, LinearSpringDashpot::name);
  scene.contact_preset = c->choice("preset", {"paper", "lammps"}, "paper");
  scene.law = make_contact_law(scene.contact_model, scene.materials.size());
  if (scene.contact_preset == "lammps" && !takes_lammps_preset(scene.law))
    c->fail("preset", fmt::format("the lammps preset applies to the {} model only",
                                  models_with_lammps_preset()));
  auto pairs = c->tables("pair");
  if (pairs.empty()) c->fail("pair", "no [[contact.pair]] given");
  for (auto& p : pairs) {
    const auto names = p.strings("materials");
    if (names.size() != 2) p.fail("materials", "expected two material names");
    std::array<std::uint8_t, 2> m{};
    for (int k = 0; k < 2; ++k) {
      const auto idx = scene.material_index(names[k]);
      if (!idx)
        p.fail("materials",
               fmt::format("material \"{}\" is not in the top-level 'materials' list", names[k]));
      m[k] = *idx;
    }
    std::visit(
        [&](auto& law) {
          using M = typename std::decay_t<decltype(law)>::model_type;
          if (law.coeffs.has(m[0], m[1]))
            p.fail("materials",
                   fmt::format("pair (\"{}\", \"{}\") is given twice", names[0], names[1]));
          law.coeffs.set(m[0], m[1], read_pair<M>(scene, p, m[0], m[1]));
        },
        scene.law);
    p.finish();
  }
  c->finish();
}

void read_planes(Scene& scene, TomlReader& root) {
  for (auto& p : root.tables("plane")) {
    PlaneWall w;
    w.name = p.string("name", fmt::format("plane {}", scene.planes.size() + 1));
    w.point = p.vec3("point");
    const Vec3 n = p.vec3("normal");
    if (norm(n) == 0.0) p.fail("normal", "must not be the zero vector");
    w.normal = n / norm(n);
    w.material = material_of(scene, p, "material");
    w.amplitude = p.number("amplitude", 0.0);
    w.omega = p.non_negative("omega", 0.0);
    w.t0 = p.number("t0", 0.0);
    p.finish();
    scene.planes.push_back(w);
  }
}

void read_basin(Scene& scene, TomlReader& root) {
  auto b = root.table("basin");
  if (!b) return;
  FishBasinSpec s;
  const auto cells = b->int3("cells", 1);
  for (int a = 0; a < 3; ++a) s.cells[a] = static_cast<int>(cells[a]);
  s.spacing = b->positive("spacing", s.spacing);
  s.radius = b->positive("radius", s.radius);
  s.wall_thickness = b->positive("wall_thickness", s.wall_thickness);
  s.wall_height = static_cast<int>(b->integer("wall_height", s.wall_height, 1, 1 << 20));
  s.side_particles = b->choice("side_wall", {"particles", "none"}, "particles") == "particles";
  s.bottom_layers = static_cast<int>(b->integer("bottom_layers", s.bottom_layers, 1, 1 << 20));
  s.fill_layers = static_cast<int>(b->integer("fill_layers", s.fill_layers, 0, 1 << 20));
  s.wall_radius = b->positive("wall_radius", s.wall_radius);
  s.radius_mean = b->positive("radius_mean", s.radius_mean);
  s.radius_sd = b->non_negative("radius_sd", s.radius_sd);
  if (3.0 * s.radius_sd >= s.radius_mean)
    b->fail("radius_sd", fmt::format("3 sd = {} must stay below the mean radius {} (radii are "
                                     "drawn within 3 sd)",
                                     3.0 * s.radius_sd, s.radius_mean));
  s.jitter = b->non_negative("jitter", s.jitter);
  s.seed = static_cast<std::uint64_t>(b->integer("seed", static_cast<std::int64_t>(s.seed), 0,
                                                 std::numeric_limits<std::int64_t>::max()));
  s.grain_material = material_of(scene, *b, "grain_material");
  s.wall_material = material_of(scene, *b, "wall_material");
  if (s.radius + s.wall_thickness > 0.5 * std::min(s.cells[0], s.cells[1]))
    b->fail("radius", fmt::format("radius + wall_thickness = {} cells does not fit in the lattice "
                                  "of {} x {} cells",
                                  s.radius + s.wall_thickness, s.cells[0], s.cells[1]));
  if (s.bottom_layers + s.wall_height > s.cells[2])
    b->fail("wall_height", fmt::format("bottom_layers + wall_height = {} exceeds cells[2] = {}",
                                       s.bottom_layers + s.wall_height, s.cells[2]));
  if (s.fill_layers + basin_wall_gap(s) > s.wall_height)
    b->fail("fill_layers", fmt::format("fill_layers = {} (+ {} empty layer next to the bottom) is "
                                       "above the wall (wall_height = {})",
                                       s.fill_layers, basin_wall_gap(s), s.wall_height));
  if (auto e = b->table("excitation")) {
    s.excitation.mode = static_cast<int>(e->integer("mode", s.excitation.mode, 0, 1000));
    s.excitation.amplitude = e->non_negative("amplitude", s.excitation.amplitude);
    s.excitation.omega = e->non_negative("omega", s.excitation.omega);
    s.excitation.t0 = e->number("t0", s.excitation.t0);
    e->finish();
  }
  // The lattice must fit in the domain.
  const auto& box = scene.sim.box;
  for (int a = 0; a < 3; ++a) {
    const double top = box.lo[a] + s.cells[a] * s.spacing;
    if (top > box.hi[a] + 1e-9 * s.spacing)
      b->fail("cells",
              fmt::format("the basin lattice reaches {} = {} on axis {}, beyond the "
                          "domain (domain.hi = {}): the container is larger than the domain",
                          a == 2 ? "z" : (a == 1 ? "y" : "x"), top, "xyz"[a], box.hi[a]));
  }
  b->finish();
  scene.basin = s;
}

void read_particles(Scene& scene, TomlReader& root) {
  for (auto& p : root.tables("particle")) {
    ParticleSpec s;
    s.position = p.vec3("position");
    s.velocity = p.vec3("velocity", {});
    s.angular_velocity = p.vec3("angular_velocity", {});
    s.radius = p.positive("radius");
    if (p.has("mass") == p.has("density")) p.fail("", "give exactly one of 'mass' and 'density'");
    s.mass = p.has("mass") ? p.positive("mass")
                           : p.positive("density") * 4.0 / 3.0 * pi * std::pow(s.radius, 3);
    s.material = material_of(scene, p, "material");
    s.kind = p.choice("kind", {"grain", "wall"}, "grain") == "wall" ? Kind::wall : Kind::grain;
    if (!scene.sim.box.contains(s.position))
      p.fail("position", fmt::format("({}, {}, {}) is outside the domain", s.position.x,
                                     s.position.y, s.position.z));
    p.finish();
    scene.particles.push_back(s);
  }
}

// [lammps_data]: atoms of a LAMMPS data file, with a material per atom type.
void read_lammps_data_section(Scene& scene, TomlReader& root) {
  auto t = root.table("lammps_data");
  if (!t) return;
  LammpsDataSpec spec;
  const std::string given = t->string("file");
  const auto base = std::filesystem::path(scene.source).parent_path();
  spec.file = std::filesystem::path(given).is_absolute() ? given : (base / given).string();
  LammpsData data;
  try {
    data = read_lammps_data(spec.file);
  } catch (const DataFileError& e) {
    t->fail("file", e.what());
  }
  const auto names = t->strings("type_materials");
  if (static_cast<int>(names.size()) != data.n_types)
    t->fail("type_materials", fmt::format("the data file has {} atom types, {} materials given",
                                          data.n_types, names.size()));
  for (const auto& n : names) {
    const auto k = scene.material_index(n);
    if (!k)
      t->fail("type_materials", fmt::format("material \"{}\" is not in the top-level "
                                            "'materials' list",
                                            n));
    spec.type_material.push_back(*k);
  }
  spec.frozen.assign(static_cast<std::size_t>(data.n_types), false);
  if (t->has("frozen_types")) {
    spec.frozen_types = t->integers("frozen_types");
    for (auto type : spec.frozen_types) {
      if (type < 1 || type > data.n_types)
        t->fail("frozen_types", fmt::format("type {} outside 1..{}", type, data.n_types));
      spec.frozen[static_cast<std::size_t>(type - 1)] = true;
    }
  }
  t->finish();
  for (const auto& a : data.atoms) {
    ParticleSpec p;
    p.position = a.x;
    p.velocity = a.v;
    p.angular_velocity = a.w;
    p.radius = 0.5 * a.diameter;
    // as LAMMPS's atom_style sphere: rmass = density * 4/3 pi r^3
    p.mass = a.density * (4.0 * pi / 3.0 * p.radius * p.radius * p.radius);
    p.material = spec.type_material[static_cast<std::size_t>(a.type - 1)];
    const bool frozen = spec.frozen[static_cast<std::size_t>(a.type - 1)];
    p.kind = frozen ? Kind::wall : Kind::grain;
    if (frozen) p.velocity = p.angular_velocity = Vec3{};
    if (!scene.sim.box.contains(p.position))
      t->fail("file", fmt::format("atom {} at ({}, {}, {}) is outside the domain", a.id, a.x.x,
                                  a.x.y, a.x.z));
    scene.particles.push_back(p);
  }
  scene.n_lammps_atoms = data.atoms.size();
  scene.lammps_data = spec;
}

// Largest centre distance of a possible contact, and which materials grains and walls use.
void check_consistency(Scene& scene, TomlReader& root) {
  double rg = 0.0, rw = 0.0;
  std::vector<bool> grain_mat(scene.materials.size()), other_mat(scene.materials.size());
  // How many grains of each material the scene may hold (2: two or more): a pair of grains of
  // one material needs coefficients only where two of them can meet.
  std::vector<std::size_t> grains_of(scene.materials.size(), 0);
  if (scene.basin) {
    rg = scene.basin->radius_mean + 3.0 * scene.basin->radius_sd;
    rw = scene.basin->wall_radius;
    grain_mat[scene.basin->grain_material] = true;
    other_mat[scene.basin->wall_material] = true;
    grains_of[scene.basin->grain_material] += 2;
  }
  for (const auto& p : scene.particles) {
    const bool grain = p.kind == Kind::grain;
    double& largest = grain ? rg : rw;
    largest = std::max(largest, p.radius);
    (grain ? grain_mat : other_mat)[p.material] = true;
    grains_of[p.material] += grain ? 1 : 0;
  }
  for (const ClumpSpec& c : scene.clumps) {
    for (const SphereMember& m : scene.shapes[static_cast<std::size_t>(c.shape)].members)
      rg = std::max(rg, c.scale * m.radius);
    grain_mat[c.material] = true;
    grains_of[c.material] += 1;
  }
  for (const auto& f : scene.fills) {
    rg = std::max(rg, f.grains.size.largest());
    grain_mat[f.grains.material] = true;
    grains_of[f.grains.material] +=
        f.amount == FillSpec::Amount::count ? static_cast<std::size_t>(f.value) : 2;
  }
  // Grains poured later need cells as wide as their contacts from the start.
  double poured = 0.0;
  for (const auto& i : scene.inserts) {
    poured = std::max(poured, i.grains.size.largest());
    grain_mat[i.grains.material] = true;
    grains_of[i.grains.material] += 2;
  }
  rg = std::max(rg, poured);
  if (poured > 0) scene.sim.min_contact_reach = std::max(2.0 * rg, rg + rw);
  // Clumps: how far a member may stand from its clump's centre (the ghosts' extra reach).
  for (const auto& f : scene.fills)
    if (f.shape >= 0) {
      const ClumpShape& shape = scene.shapes[static_cast<std::size_t>(f.shape)];
      if (shape.members.size() > 1)
        scene.sim.clump_reach =
            std::max(scene.sim.clump_reach,
                     shape.scaled(f.grains.size.largest() / shape.bounding_radius).member_reach());
    }
  for (const auto& i : scene.inserts)
    scene.sim.clump_reach = std::max(scene.sim.clump_reach, i.clump_reach());
  for (const ClumpSpec& c : scene.clumps)
    scene.sim.clump_reach =
        std::max(scene.sim.clump_reach,
                 scene.shapes[static_cast<std::size_t>(c.shape)].scaled(c.scale).member_reach());
  // (a scene without grains may continue a saved state: a run that builds it from t = 0
  // refuses it, build_simulation())
  scene.largest_grain_radius = rg;
  for (const auto& w : scene.planes) other_mat[w.material] = true;
  for (const auto& w : scene.walls) other_mat[wall_material(w)] = true;
  for (int a = 0; a < 3; ++a)
    if (scene.sim.box.boundary[a] == Boundary::wall) other_mat[scene.sim.box_wall_material] = true;

  const double reach = std::max(2.0 * rg, rg + rw);
  const bool skin_given = scene.sim.skin >= 0.0;
  scene.skin_from_grains = !skin_given;
  if (!skin_given) scene.sim.skin = default_skin_fraction * 2.0 * rg;
  auto& c = scene.sim;
  if (c.cell_size > 0.0 && c.cell_size < reach) {
    auto d = root.table("domain");
    d->fail("cell_size", fmt::format("{} is smaller than the largest contact distance {} (the "
                                     "largest grain diameter, or grain + wall radius)",
                                     c.cell_size, reach));
  }
  const double edge = std::max(c.cell_size, reach + c.skin);
  for (int a = 0; a < 3; ++a)
    if (c.box.periodic(a) && c.box.length(a) < 2.0 * edge) {
      auto d = root.table("domain");
      // (name the key that made the cells too wide, where it is not the domain)
      const char* key = c.cell_size >= reach + c.skin  ? "cell_size"
                        : skin_given && c.skin > reach ? "skin"
                                                       : "hi";
      d->fail(key, fmt::format("periodic axis {} is {:.4g} long, less than two linked cells of "
                               "{:.4g} (the largest contact distance {:.4g}{}); a periodic axis "
                               "needs two cells: make it at least {:.4g} long{}",
                               "xyz"[a], c.box.length(a), edge, reach,
                               c.cell_size > 0.0 ? fmt::format(", cell_size {:.4g}", c.cell_size)
                                                 : fmt::format(" plus the skin {:.4g}", c.skin),
                               2.0 * edge,
                               std::string_view(key) == "hi" ? "" : ", or make the cells smaller"));
    }
  // Cells much wider than a contact hold many grains, and every pair within reach of a cell's
  // neighbours is listed: warn where they are more than three contact distances wide (27 times
  // the grains of the smallest cells).
  if (rg > 0.0 && edge > 3.0 * reach)
    scene.warnings.push_back(fmt::format(
        "the linked cells are {:.4g} wide, {:.3g} times the largest contact distance {:.4g} (the "
        "largest grain diameter {:.4g}{}): each holds up to about {:.0f} grains and the lists "
        "every "
        "pair within {:.4g}, so the run may be many times slower than it needs to be. The "
        "default skin is {} of the largest grain diameter",
        edge, edge / reach, reach, 2.0 * rg,
        c.cell_size > 0.0 ? fmt::format(", cell_size {:.4g}", c.cell_size)
                          : fmt::format(", [domain] skin {:.4g}", c.skin),
        0.74 * std::pow(edge / (2.0 * rg), 3) / (std::numbers::pi / 6.0), reach + c.skin,
        default_skin_fraction));
  // Every pair that can touch needs coefficients.
  const auto has_pair = [&](std::size_t a, std::size_t b) {
    return std::visit([&](const auto& law) { return law.coeffs.has(a, b); }, scene.law);
  };
  for (std::size_t a = 0; a < scene.materials.size(); ++a) {
    if (!grain_mat[a]) continue;
    for (std::size_t b = 0; b < scene.materials.size(); ++b)
      if ((grain_mat[b] || other_mat[b]) && !has_pair(a, b) &&
          !(a == b && grains_of[a] < 2 && !other_mat[a])) {
        auto contact = root.table("contact");
        contact->fail("pair",
                      fmt::format("no [[contact.pair]] for materials (\"{}\", \"{}\"), which "
                                  "can touch",
                                  scene.materials[a], scene.materials[b]));
      }
  }
}

} // namespace

void size_for_saved_grains(Scene& scene, double largest_grain_radius) {
  if (scene.largest_grain_radius > 0.0 || !(largest_grain_radius > 0.0)) return;
  scene.largest_grain_radius = largest_grain_radius;
  scene.sim.min_contact_reach = std::max(scene.sim.min_contact_reach, 2.0 * largest_grain_radius);
  if (scene.skin_from_grains) scene.sim.skin = default_skin_fraction * 2.0 * largest_grain_radius;
}

Scene read_scene_text(std::string_view text, const std::string& source, bool lines) {
  const toml::table doc = parse_toml(text, source);
  TomlReader root(doc, "", source, lines);
  Scene scene;
  scene.source = source;
  scene.run.name = std::filesystem::path(source).stem().string();
  read_materials(scene, root);
  read_run(scene, root);
  read_output(scene, root);
  read_checkpoint_settings(scene, root);
  read_domain(scene, root);
  read_contact(scene, root);
  read_planes(scene, root);
  read_shaped_walls(scene, root);
  read_basin(scene, root);
  read_analysis(scene, root);
  read_lammps_data_section(scene, root);
  read_particles(scene, root);
  read_shapes(scene, root); // (before the fills that name them)
  read_sources(scene, root);
  read_measures(scene, root);
  read_coarse_grains(scene, root);
  root.finish();
  check_consistency(scene, root);
  return scene;
}

Scene read_scene_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(fmt::format("{}: cannot open the scene file", path));
  std::ostringstream text;
  text << in.rdbuf();
  return read_scene_text(text.str(), path);
}

} // namespace yuxi
