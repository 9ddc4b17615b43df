#include "io/source_scene_reader.hpp"

#include "core/ball_volume.hpp"
#include "core/units.hpp"
#include "io/shape_scene_reader.hpp"
#include "io/wall_scene_reader.hpp"

#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <limits>
#include <string_view>

namespace yuxi {
namespace {

Region read_mesh_region(const Scene& scene, TomlReader& r) {
  PlacedMesh placed = read_placed_mesh(scene, r);
  try {
    MeshRegion m(std::move(placed.mesh), placed.file);
    m.scale = placed.scale, m.rotate_axis = placed.rotate_axis;
    m.rotate_degrees = placed.rotate_degrees, m.translate = placed.translate;
    return Region(std::move(m));
  } catch (const std::invalid_argument& e) {
    r.fail("file", fmt::format("{}: {}", placed.file, e.what()));
  }
}

SizeDistribution read_size(TomlReader& t) {
  SizeDistribution d;
  if (t.has("radius")) {
    if (t.has("size")) t.fail("size", "give either 'radius' (one size) or a [size] table");
    d.radius = t.positive("radius");
    return d;
  }
  auto s = t.table("size");
  if (!s) t.fail("radius", "give the grains' 'radius', or a [size] table with a distribution");
  using Kind = SizeDistribution::Kind;
  const std::string kind = s->choice(
      "distribution", {"constant", "uniform", "normal", "lognormal", "discrete"}, "constant");
  if (kind == "constant") {
    d.radius = s->positive("radius");
  } else if (kind == "uniform") {
    d.kind = Kind::uniform;
    d.min = s->positive("min");
    d.max = s->positive("max");
  } else if (kind == "normal" || kind == "lognormal") {
    d.kind = kind == "normal" ? Kind::normal : Kind::lognormal;
    d.mean = s->positive("mean");
    d.sd = s->number("sd");
    if (!(d.sd >= 0)) s->fail("sd", fmt::format("must not be negative (got {})", d.sd));
    // Truncated at 3 sd by default (the lognormal's sd is the radius's own).
    d.min = s->positive("min", std::max(d.mean - 3 * d.sd, 0.05 * d.mean));
    d.max = s->positive("max", d.mean + 3 * d.sd);
  } else {
    d.kind = Kind::discrete;
    d.radii = s->numbers("radii");
    d.weights = s->numbers("weights");
    d.by_mass = s->choice("weights_by", {"number", "mass"}, "number") == "mass";
  }
  try {
    d.validate();
  } catch (const std::invalid_argument& e) {
    s->fail("distribution", e.what());
  }
  s->finish();
  return d;
}

// Sizes, material, density, velocity and seed of the grains of a [[fill]] or [[insert]].
// Fixed wall particles (`walls`) need no density: it defaults to 1.
GrainKind read_grains(const Scene& scene, TomlReader& t, std::uint64_t default_seed,
                      bool walls = false) {
  GrainKind g;
  g.size = read_size(t);
  g.material = material_of(scene, t, "material");
  const double material_density = scene.material_properties[g.material].density;
  if (t.has("density")) {
    g.density = t.positive("density");
  } else if (std::isfinite(material_density)) {
    g.density = material_density;
  } else if (walls) {
    g.density = 1.0;
  } else {
    t.fail("density", fmt::format("give the grains' density here or in [material.{}]",
                                  scene.materials[g.material]));
  }
  g.velocity = t.vec3("velocity", Vec3{});
  g.velocity_spread = t.non_negative("velocity_spread", 0.0);
  g.seed = static_cast<std::uint64_t>(t.integer("seed", static_cast<std::int64_t>(default_seed), 0,
                                                std::numeric_limits<std::int64_t>::max()));
  return g;
}

// The index of the [[shape]] that key `shape` names; the grains drawn are its bounding balls,
// whose mass is the clump's (volume_fraction). One member: a sphere, the grains as they would be
// without the shape.
int read_shape_key(const Scene& scene, TomlReader& t, GrainKind& grains) {
  const int index = shape_named(scene, t);
  const ClumpShape& shape = scene.shapes[static_cast<std::size_t>(index)];
  if (shape.members.size() > 1)
    grains.volume_fraction = shape.volume / ball_volume(shape.bounding_radius);
  return index;
}

void read_fill(Scene& scene, TomlReader& t, std::size_t index) {
  FillSpec f;
  f.name = fmt::format("{} (fill[{}])", t.where(""), index + 1);
  f.region = read_region(scene, t);
  f.walls = t.choice("kind", {"grain", "wall"}, "grain") == "wall";
  f.grains = read_grains(scene, t, 2008 + index, f.walls);
  if (t.has("shape")) {
    if (f.walls) t.fail("shape", "wall particles are spheres: no shape for kind = \"wall\"");
    f.shape = read_shape_key(scene, t, f.grains);
  }
  if (f.walls && (t.has("velocity") || t.has("velocity_spread")))
    t.fail(t.has("velocity") ? "velocity" : "velocity_spread",
           "wall particles do not move: no velocity for kind = \"wall\"");
  const int amounts = t.has("count") + t.has("packing_fraction") + t.has("mass");
  if (amounts != 1) t.fail("count", "give exactly one of 'count', 'packing_fraction' and 'mass'");
  if (t.has("count")) {
    f.amount = FillSpec::Amount::count;
    f.value = static_cast<double>(t.integer("count", 0, 1, std::int64_t{1} << 31));
  } else if (t.has("packing_fraction")) {
    f.amount = FillSpec::Amount::packing_fraction;
    f.value = t.positive("packing_fraction");
    if (f.value >= pi / 6.0 + 1e-12)
      t.fail("packing_fraction",
             fmt::format("{} is beyond what the cubic lattice holds (pi/6 = 0.524): pour the "
                         "grains with [[insert]] and let them settle",
                         f.value));
  } else {
    f.amount = FillSpec::Amount::mass;
    f.value = t.positive("mass");
  }
  f.placement = t.choice("placement", {"random", "lattice"}, "random") == "lattice"
                    ? FillSpec::Placement::lattice
                    : FillSpec::Placement::random;
  f.jitter = t.non_negative("jitter", 0.0);
  if (f.jitter > 0 && f.placement != FillSpec::Placement::lattice)
    t.fail("jitter", "applies to placement = \"lattice\" only");
  if (t.has("attempts") && f.placement != FillSpec::Placement::random)
    t.fail("attempts", "applies to placement = \"random\" only");
  f.attempts_per_grain = static_cast<int>(t.integer("attempts", f.attempts_per_grain, 1, 1000000));
  if (f.placement == FillSpec::Placement::random &&
      f.amount == FillSpec::Amount::packing_fraction && f.value > random_fill_limit)
    t.fail("packing_fraction",
           fmt::format("{} is beyond what random placement without overlap reaches (it jams near "
                       "0.35-0.38): use placement = \"lattice\", or pour the grains with "
                       "[[insert]] and let them settle",
                       f.value));
  t.finish();
  scene.fills.push_back(std::move(f));
}

void read_insert(Scene& scene, TomlReader& t, std::size_t index) {
  InsertSpec s;
  s.name = t.string("name", fmt::format("insert[{}]", index + 1));
  s.region = read_region(scene, t);
  s.grains = read_grains(scene, t, 3008 + index);
  if (t.has("shape")) {
    s.shape = read_shape_key(scene, t, s.grains);
    s.clump = scene.shapes[static_cast<std::size_t>(s.shape)];
  }
  if (t.has("rate") == t.has("mass_rate"))
    t.fail("rate", "give exactly one of 'rate' (grains per time) and 'mass_rate' (mass per time)");
  s.by_mass = t.has("mass_rate");
  s.rate = t.positive(s.by_mass ? "mass_rate" : "rate");
  s.start = t.non_negative("start", 0.0);
  s.end = t.number("end", std::numeric_limits<double>::infinity());
  if (!(s.end > s.start)) t.fail("end", fmt::format("must come after start = {}", s.start));
  s.total = t.integer("total", -1, 1, std::numeric_limits<std::int64_t>::max());
  // 500 steps: a batch forces a list build, which costs about ten steps (docs/performance.md).
  s.interval = t.positive("interval", 500 * scene.sim.dt);
  if (s.interval < scene.sim.dt) t.fail("interval", "must be at least one time step");
  s.attempts = static_cast<int>(t.integer("attempts", s.attempts, 1, 10000));
  s.held = t.boolean("held", false);
  // One batch must fit in the region by random placement (a batch is at most the total).
  const double volume = s.region.volume_in(scene.sim.box);
  // (a clump's: its bounding ball placed, its own volume weighed)
  const double grain_volume = 4.0 / 3.0 * pi * s.grains.size.mean_cube();
  const double grain_mass = s.grains.density * s.grains.volume_fraction * grain_volume;
  double batch = s.rate * s.interval / (s.by_mass ? grain_mass : 1.0);
  if (s.total >= 0) batch = std::min(batch, static_cast<double>(s.total));
  if (batch * grain_volume > random_fill_limit * volume)
    t.fail(s.by_mass ? "mass_rate" : "rate",
           fmt::format("a batch of {:.4g} grains every {:.4g} (interval) would fill a packing "
                       "fraction of {:.3f} of the region ({:.4g} of volume), beyond the 0.38 "
                       "at which random placement jams: lower the rate, shorten the interval or "
                       "enlarge the region",
                       batch, s.interval, batch * grain_volume / volume, volume));
  t.finish();
  scene.inserts.push_back(std::move(s));
}

void read_outlet(Scene& scene, TomlReader& t, std::size_t index) {
  OutletSpec o;
  o.name = t.string("name", fmt::format("outlet[{}]", index + 1));
  o.region = read_region(scene, t);
  t.finish();
  scene.outlets.push_back(std::move(o));
}

} // namespace

Region read_region(const Scene& scene, TomlReader& t, std::string_view key) {
  auto r = t.table(key);
  if (!r)
    t.fail(key, "missing region table (shape = \"box\", \"cylinder\", \"sphere\", \"mesh\" "
                "or \"half_space\")");
  const std::string shape =
      r->choice("shape", {"box", "cylinder", "sphere", "mesh", "half_space"}, "box");
  Region region;
  if (shape == "box") {
    BoxRegion b{r->vec3("lo"), r->vec3("hi")};
    for (int a = 0; a < 3; ++a)
      if (!(b.hi[a] > b.lo[a]))
        r->fail("hi", fmt::format("must exceed 'lo' on every axis (axis {})", "xyz"[a]));
    region = Region(b);
  } else if (shape == "cylinder") {
    CylinderRegion c;
    c.center = r->vec3("center");
    c.axis = unit_vector(*r, "axis", Vec3{0, 0, 1});
    c.radius = r->positive("radius");
    c.lo = r->number("lo");
    c.hi = r->number("hi");
    if (!(c.hi > c.lo)) r->fail("hi", "must be above lo");
    region = Region(c);
  } else if (shape == "sphere") {
    region = Region(SphereRegion{r->vec3("center"), r->positive("radius")});
  } else if (shape == "mesh") {
    region = read_mesh_region(scene, *r);
  } else {
    region = Region(HalfSpaceRegion{r->vec3("point"), unit_vector(*r, "normal", Vec3{0, 0, 1})});
  }
  if (!(region.volume_in(scene.sim.box) > 0))
    r->fail("shape", fmt::format("the region ({}) does not meet the domain", region.describe()));
  r->finish();
  return region;
}

void read_sources(Scene& scene, TomlReader& root) {
  for (auto& t : root.tables("fill")) read_fill(scene, t, scene.fills.size());
  for (auto& t : root.tables("insert")) read_insert(scene, t, scene.inserts.size());
  for (auto& t : root.tables("outlet")) read_outlet(scene, t, scene.outlets.size());
}

const InsertSpec& add_insert_table(Scene& scene, std::string_view text, const std::string& source) {
  const toml::table doc = parse_toml(text, source);
  TomlReader root(doc, "", source);
  auto tables = root.tables("insert");
  if (tables.size() != 1) root.fail("insert", "expected one [[insert]] table");
  read_insert(scene, tables.front(), scene.inserts.size());
  root.finish();
  return scene.inserts.back();
}

} // namespace yuxi
