// The sources part: batches of an insert placed at the list builds, outlets' tallies, the
// inserts steered from outside, and the sources' section of a checkpoint.
#include "sim/sources.hpp"

#include "core/random.hpp"
#include "scene/ball_hash.hpp"
#include "sim/energy_ledger.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>

namespace yuxi {
namespace {

// The random stream of one batch of an insert: the same candidates on every number of ranks,
// and a resumed run draws the batches it has not drawn yet.
Random batch_stream(std::uint64_t seed, std::int64_t batch) {
  return Random(seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(batch) + 1);
}

template <class Archive> void strings(Archive& ar, std::vector<std::string>& v) {
  std::uint64_t n = v.size();
  ar.value(n);
  if constexpr (Archive::loading) {
    if (n > (std::uint64_t{1} << 24)) throw ArchiveError("an impossible count of names");
    v.assign(n, std::string{});
  }
  for (std::string& s : v) ar.string(s);
}

} // namespace

void Sources::set(std::vector<InsertSpec> inserts, std::vector<OutletSpec> outlets) {
  inserts_ = std::move(inserts);
  outlets_ = std::move(outlets);
  insert_progress_.assign(inserts_.size(), InsertProgress{});
  owed_grains_.assign(inserts_.size(), {});
  for (std::size_t k = 0; k < inserts_.size(); ++k)
    if (inserts_[k].held) insert_progress_[k].halted = 1; // (until start_insert)
  outlet_part_.assign(outlets_.size(), OutletPart{});
}

Sources::BatchSteps Sources::batch_steps(std::size_t k, double dt) const {
  const InsertSpec& s = inserts_[k];
  const std::int64_t first = insert_progress_[k].first_step >= 0
                                 ? insert_progress_[k].first_step
                                 : std::max<std::int64_t>(1, std::llround(s.start / dt));
  const std::int64_t every = std::max<std::int64_t>(1, std::llround(s.interval / dt));
  const std::int64_t last =
      std::isfinite(s.end) ? std::llround(s.end / dt) : std::numeric_limits<std::int64_t>::max();
  return {first, every, last};
}

bool Sources::batch_due(std::size_t k, std::int64_t step, double dt) const {
  const InsertProgress& p = insert_progress_[k];
  const bool full = inserts_[k].total >= 0 && p.grains >= inserts_[k].total;
  const BatchSteps b = batch_steps(k, dt);
  return p.halted == 0 && !full && step >= b.first && step <= b.last &&
         (step - b.first) % b.every == 0;
}

bool Sources::insertion_due(std::int64_t step, double dt) const {
  for (std::size_t k = 0; k < inserts_.size(); ++k)
    if (batch_due(k, step, dt)) return true;
  return false;
}

void Sources::insert_due_batches(ParticleStore& s, ClumpBodies& clumps,
                                 const SimulationConfig& config, const Decomposition& decomp,
                                 const Comm& comm, const std::vector<PlaneWall>& planes, double t,
                                 std::int64_t step, Books books) {
  for (std::size_t k = 0; k < inserts_.size(); ++k)
    if (batch_due(k, step, config.dt))
      insert_batch(k, s, clumps, config, decomp, comm, planes, t, step, books);
}

void Sources::adopt(const std::vector<std::string>& insert_names,
                    const std::vector<InsertProgress>& inserts,
                    const std::vector<std::vector<OwedGrain>>& owed,
                    const std::vector<std::string>& outlet_names,
                    const std::vector<OutletPart>& outlets) {
  // (a handful of sources: a search by name each)
  std::vector<InsertProgress> progress(inserts_.size());
  std::vector<std::vector<OwedGrain>> owed_grains(inserts_.size());
  for (std::size_t k = 0; k < inserts_.size(); ++k) {
    if (inserts_[k].held) progress[k].halted = 1;
    for (std::size_t j = 0; j < insert_names.size(); ++j)
      if (insert_names[j] == inserts_[k].name) {
        progress[k] = inserts[j];
        if (j < owed.size()) owed_grains[k] = owed[j];
      }
  }
  owed_grains_ = std::move(owed_grains);
  std::vector<OutletPart> parts(outlets_.size());
  for (std::size_t k = 0; k < outlets_.size(); ++k)
    for (std::size_t j = 0; j < outlet_names.size(); ++j)
      if (outlet_names[j] == outlets_[k].name) parts[k] = outlets[j];
  insert_progress_ = std::move(progress);
  outlet_part_ = std::move(parts);
}

void Sources::start_insert(std::size_t k, std::int64_t step, double dt) {
  const InsertSpec& s = inserts_.at(k);
  InsertProgress& p = insert_progress_.at(k);
  if (p.halted == 2)
    throw std::invalid_argument(fmt::format("insert '{}' was stopped for good", s.name));
  if (s.total >= 0 && p.grains >= s.total)
    throw std::invalid_argument(
        fmt::format("insert '{}' has poured its total of {} grains", s.name, s.total));
  if (std::isfinite(s.end) && step + 1 > std::llround(s.end / dt))
    throw std::invalid_argument(
        fmt::format("insert '{}' ends at t = {}, which has passed", s.name, s.end));
  p.first_step = step + 1;
  p.grains_before = p.grains;
  p.mass_before = p.mass;
  p.halted = 0;
}

void Sources::pause_insert(std::size_t k) {
  if (insert_progress_.at(k).halted == 2)
    throw std::invalid_argument(fmt::format("insert '{}' was stopped for good", inserts_[k].name));
  insert_progress_[k].halted = 1;
}

void Sources::stop_insert(std::size_t k) {
  insert_progress_.at(k).halted = 2;
}

void Sources::check_new_name(const std::string& name) const {
  for (const InsertSpec& s : inserts_)
    if (s.name == name)
      throw std::invalid_argument(fmt::format("an insert named '{}' exists already", s.name));
}

void Sources::add_insert(InsertSpec insert, std::int64_t step, double dt) {
  check_new_name(insert.name);
  InsertProgress p;
  if (insert.held) p.halted = 1;
  p.first_step = std::max(step + 1, std::max<std::int64_t>(1, std::llround(insert.start / dt)));
  inserts_.push_back(std::move(insert));
  insert_progress_.push_back(p);
  owed_grains_.emplace_back();
}

void Sources::withdraw_last_insert() {
  inserts_.pop_back();
  insert_progress_.pop_back();
  owed_grains_.pop_back();
}

void Sources::insert_batch(std::size_t source, ParticleStore& store, ClumpBodies& clumps,
                           const SimulationConfig& config, const Decomposition& decomp,
                           const Comm& comm, const std::vector<PlaneWall>& planes, double t,
                           std::int64_t step, Books books) {
  const InsertSpec& s = inserts_[source];
  InsertProgress& progress = insert_progress_[source];
  const double dt = config.dt;
  const BatchSteps b = batch_steps(source, dt);
  // What is due by the end of this batch's interval, from the pouring under way: a count, or
  // grains until the mass is.
  const double elapsed = static_cast<double>(step - b.first + b.every) * dt;
  Random rng = batch_stream(s.grains.seed, progress.batches);
  ++progress.batches;
  struct Due {
    double radius;
    Vec3 velocity;
  };
  // The grains owed by the last batch first, as they were drawn, then new ones.
  std::vector<Due> due;
  std::vector<OwedGrain>& owed = owed_grains_[source];
  if (s.by_mass) {
    double mass = progress.mass;
    const double target = progress.mass_before + s.rate * elapsed;
    for (const OwedGrain& o : owed) {
      if (!(mass < target)) break;
      due.push_back({o.radius, o.velocity});
      mass += s.grains.mass_of(o.radius);
    }
    while (mass < target && due.size() < 1000000) {
      const double r = s.grains.size.draw(rng);
      due.push_back({r, s.grains.draw_velocity(rng)});
      mass += s.grains.mass_of(r);
    }
  } else {
    auto target =
        progress.grains_before + static_cast<std::int64_t>(std::floor(s.rate * elapsed + 1e-9));
    if (s.total >= 0) target = std::min(target, s.total);
    std::int64_t n = progress.grains;
    for (std::size_t k = 0; k < owed.size() && n < target; ++k, ++n)
      due.push_back({owed[k].radius, owed[k].velocity});
    for (; n < target; ++n) {
      const double r = s.grains.size.draw(rng);
      due.push_back({r, s.grains.draw_velocity(rng)});
    }
  }
  owed.clear();
  if (due.empty()) return;
  // Candidate places: `attempts` for each due grain, from the batch's stream.
  const std::size_t attempts = static_cast<std::size_t>(std::max(1, s.attempts));
  std::vector<Vec3> places(due.size() * attempts);
  for (auto& p : places) p = s.region.sample(rng, config.box).value_or(Vec3{NAN, NAN, NAN});
  // Refused where the ball leaves the region or the domain, meets a plane, or overlaps a
  // particle this rank owns; every rank judges its own particles, and the refusals are
  // combined (max) so that every rank takes the same candidates. Positions are wrapped, and a
  // ball near a periodic face is looked for at its images across it too.
  const Box& box = config.box;
  double r_max = s.grains.size.largest();
  std::vector<double> refused(places.size(), 0.0);
  Vec3 lo, hi;
  s.region.bounds_in(box, lo, hi);
  double reach = 2.0 * r_max;
  for (std::size_t i = 0; i < store.n_owned(); ++i)
    reach = std::max(reach, store.radius[i] + r_max);
  BallHash near(reach);
  for (std::size_t i = 0; i < store.n_owned(); ++i) {
    const Vec3 x = box.wrap(store.x[i]);
    bool is_near = true; // (any distance along a periodic axis: an image may come near)
    for (int a = 0; a < 3; ++a)
      is_near = is_near && (box.periodic(a) || (x[a] >= lo[a] - reach && x[a] <= hi[a] + reach));
    if (is_near) near.add(x, store.radius[i]);
  }
  const auto overlaps = [&](const BallHash& balls, const Vec3& x, double r) {
    for (const Vec3& image : box.images_within(x, reach))
      if (balls.overlaps(image, r)) return true;
    return false;
  };
  for (std::size_t c = 0; c < places.size(); ++c) {
    const Vec3& x = places[c];
    const double r = due[c / attempts].radius;
    bool bad = !is_finite(x) || !box.contains(x) || !s.region.contains_sphere_in(x, r, box) ||
               overlaps(near, x, r);
    for (const PlaneWall& w : planes) bad = bad || w.distance(x, t) < r;
    refused[c] = bad ? 1.0 : 0.0;
  }
  if (comm.size() > 1) comm.max(refused.data(), static_cast<int>(refused.size()));
  // The same choice on every rank: for each due grain its first free place, clear of the
  // grains taken before it in this batch.
  BallHash taken(2.0 * r_max);
  const Vec3 g = potential_gravity(config);
  store.clear_ghosts();
  std::int64_t placed = 0;
  for (std::size_t j = 0; j < due.size(); ++j) {
    bool found = false;
    for (std::size_t a = 0; a < attempts; ++a) {
      const std::size_t c = j * attempts + a;
      const Vec3& x = places[c];
      if (refused[c] > 0.0 || overlaps(taken, x, due[j].radius)) continue;
      found = true;
      taken.add(x, due[j].radius);
      ++placed;
      // The step's second half kick (gravity alone, until its contacts are computed) brings
      // the velocity to the one drawn: it starts half a kick behind. Its kinetic and potential
      // energy come from outside the equations of motion.
      const Vec3 v_start = due[j].velocity - (0.5 * dt) * config.gravity;
      if (s.pours_clumps()) {
        const Quaternion turn = random_orientation(rng); // (drawn on every rank alike)
        PlacedClump clump =
            make_clump(s.clump.scaled(due[j].radius / s.clump.bounding_radius), s.grains.density,
                       s.grains.material, next_gid_, x, turn, v_start);
        ClumpBody& body = clump.body;
        next_gid_ += static_cast<GlobalId>(clump.members.size());
        progress.mass += body.mass;
        // (its owner: the rank of its anchor member, sim/exchange.hpp)
        if (!decomp.owns(config.box.wrap(clump.members[body.anchor()].position))) break;
        for (std::size_t k = 0; k < clump.members.size(); ++k)
          store.add(clump.members[k], body.id + static_cast<GlobalId>(k));
        body.shape = s.shape;
        body.force = body.mass * config.gravity;
        books.inserted += 0.5 * body.mass * norm2(due[j].velocity) - body.mass * dot(g, body.x);
        clumps.add(std::move(body));
        break;
      }
      const GlobalId id = next_gid_++;
      const double m = s.grains.mass_of(due[j].radius);
      progress.mass += m;
      if (decomp.owns(config.box.wrap(x))) {
        ParticleSpec p;
        p.position = x;
        p.radius = due[j].radius;
        p.mass = m;
        p.material = s.grains.material;
        p.velocity = v_start;
        const std::size_t i = store.add(p, id);
        store.f[i] = m * config.gravity;
        books.inserted += 0.5 * m * norm2(due[j].velocity) - m * dot(g, x);
      }
      break;
    }
    if (!found) owed.push_back({due[j].radius, due[j].velocity});
  }
  progress.grains += placed;
  progress.owed = static_cast<std::int64_t>(owed.size());
}

void Sources::drain_outlets(ParticleStore& s, ClumpBodies& clumps, const Box& box,
                            const Vec3& g_potential, Books books) {
  // The outlet that holds x (outlets_.size(): none).
  const auto outlet_of = [&](const Vec3& x) {
    const Vec3 at = box.wrap(x);
    std::size_t k = 0;
    while (k < outlets_.size() && !outlets_[k].region.contains(at)) ++k;
    return k;
  };
  const auto take = [&](std::size_t k, double mass, double energy) {
    books.removed += energy;
    ++outlet_part_[k].grains;
    outlet_part_[k].mass += mass;
  };
  std::vector<std::size_t> gone;
  for (std::size_t i = 0; i < s.n_owned(); ++i) {
    if (!s.is_grain(i) || s.body[i] >= 0) continue; // (a clump's member: its clump, below)
    const std::size_t k = outlet_of(s.x[i]);
    if (k == outlets_.size()) continue;
    gone.push_back(i);
    take(k, s.mass[i], mechanical_energy(s, i, g_potential));
  }
  std::vector<std::size_t> bodies;
  for (std::size_t b = 0; b < clumps.size(); ++b) {
    const std::size_t k = outlet_of(clumps.bodies()[b].x);
    if (k == outlets_.size()) continue;
    bodies.push_back(b);
    take(k, clumps.bodies()[b].mass, clumps.mechanical_energy(b, g_potential));
  }
  if (!bodies.empty()) {
    const std::vector<std::size_t> members = clumps.remove(s, bodies);
    gone.insert(gone.end(), members.begin(), members.end());
    std::sort(gone.begin(), gone.end());
  }
  if (!gone.empty()) s.remove_owned(gone);
}

std::vector<Sources::Tally> Sources::inflow() const {
  std::vector<Tally> out;
  for (std::size_t k = 0; k < inserts_.size(); ++k)
    out.push_back({inserts_[k].name, insert_progress_[k].grains, insert_progress_[k].mass,
                   insert_progress_[k].owed});
  return out;
}

std::vector<Sources::Tally> Sources::outflow(const Comm& comm) const {
  std::vector<double> sums;
  for (const OutletPart& p : outlet_part_)
    sums.insert(sums.end(), {static_cast<double>(p.grains), p.mass});
  if (!sums.empty()) comm.sum(sums.data(), static_cast<int>(sums.size()));
  std::vector<Tally> out;
  for (std::size_t k = 0; k < outlets_.size(); ++k)
    out.push_back({outlets_[k].name, std::llround(sums[2 * k]), sums[2 * k + 1], 0});
  return out;
}

void Sources::save(ArchiveWriter& ar) const {
  ar.value(next_gid_);
  std::vector<std::string> insert_names, outlet_names;
  for (const InsertSpec& s : inserts_) insert_names.push_back(s.name);
  for (const OutletSpec& s : outlets_) outlet_names.push_back(s.name);
  std::vector<InsertProgress> inserts = insert_progress_;
  std::vector<OutletPart> outlets = outlet_part_;
  strings(ar, insert_names);
  ar.vector(inserts);
  strings(ar, outlet_names);
  ar.vector(outlets);
  write_owed(ar);
}

void Sources::write_owed(ArchiveWriter& ar) const {
  for (const std::vector<OwedGrain>& owed : owed_grains_) ar.vector(owed);
}

std::vector<std::vector<Sources::OwedGrain>> Sources::read_owed(ArchiveReader& ar,
                                                                std::size_t inserts) {
  std::vector<std::vector<OwedGrain>> owed(inserts);
  for (std::vector<OwedGrain>& o : owed) {
    ar.vector(o);
    for (const OwedGrain& g : o)
      if (!(g.radius > 0 && std::isfinite(g.radius) && is_finite(g.velocity)))
        throw ArchiveError("an insert's owed grain is impossible (corrupt)");
  }
  return owed;
}

void Sources::load(ArchiveReader& ar, std::uint32_t layout) {
  if (layout < 6) return; // (none under way)
  ar.value(next_gid_);
  std::vector<std::string> insert_names, outlet_names;
  for (const InsertSpec& s : inserts_) insert_names.push_back(s.name);
  for (const OutletSpec& s : outlets_) outlet_names.push_back(s.name);
  std::vector<InsertProgress> inserts;
  std::vector<OutletPart> outlets;
  if (layout < 8) { // by position, unnamed: this scene's names where the counts agree
    std::vector<InsertProgressV6> old;
    ar.vector(old);
    ar.vector(outlets);
    inserts.assign(old.size(), InsertProgress{});
    for (std::size_t k = 0; k < old.size(); ++k)
      inserts[k].batches = old[k].batches, inserts[k].grains = old[k].grains,
      inserts[k].owed = old[k].owed, inserts[k].mass = old[k].mass;
    if (inserts.size() != inserts_.size()) inserts.clear(), insert_names.clear();
    if (outlets.size() != outlets_.size()) outlets.clear(), outlet_names.clear();
  } else {
    strings(ar, insert_names);
    ar.vector(inserts);
    strings(ar, outlet_names);
    ar.vector(outlets);
  }
  if (insert_names.size() != inserts.size() || outlet_names.size() != outlets.size())
    throw ArchiveError("the sources' names and states differ in number (corrupt)");
  const auto owed = read_owed(ar, layout >= 11 ? inserts.size() : 0);
  adopt(insert_names, inserts, owed, outlet_names, outlets);
}

void Sources::add_outlet_parts(OutletParts& sum) const {
  sum.grains.resize(outlet_part_.size(), 0);
  sum.mass.resize(outlet_part_.size(), 0.0);
  for (std::size_t o = 0; o < outlet_part_.size(); ++o) {
    sum.grains[o] += outlet_part_[o].grains;
    sum.mass[o] += outlet_part_[o].mass;
  }
}

void Sources::set_outlet_parts(const OutletParts& sum) {
  outlet_part_.assign(outlets_.size(), OutletPart{});
  for (std::size_t o = 0; o < outlet_part_.size() && o < sum.grains.size(); ++o)
    outlet_part_[o] = {sum.grains[o], sum.mass[o]};
}

void Sources::agree_over(const Comm& comm, bool loaded) {
  // The owed grains, from the first rank that loaded a section (every section holds them).
  {
    ArchiveWriter mine;
    write_owed(mine);
    const std::string agreed = comm.first_error(loaded ? "L" + mine.data() : std::string());
    if (!agreed.empty()) {
      ArchiveReader ar(std::string_view(agreed).substr(1));
      owed_grains_ = read_owed(ar, owed_grains_.size());
    }
  }
  std::vector<double> numbers{loaded ? static_cast<double>(next_gid_) : -HUGE_VAL};
  constexpr int fields = InsertProgress::n_numbers;
  for (const InsertProgress& p : insert_progress_)
    for (double v :
         {static_cast<double>(p.batches), static_cast<double>(p.grains),
          static_cast<double>(p.owed), p.mass, static_cast<double>(p.first_step),
          static_cast<double>(p.grains_before), p.mass_before, static_cast<double>(p.halted)})
      numbers.push_back(loaded ? v : -HUGE_VAL);
  comm.max(numbers.data(), static_cast<int>(numbers.size()));
  next_gid_ = static_cast<GlobalId>(numbers[0]);
  const auto count = [](double v) { return static_cast<std::int64_t>(v); };
  for (std::size_t k = 0; k < insert_progress_.size(); ++k) {
    const double* v = &numbers[1 + fields * k];
    insert_progress_[k] = {count(v[0]), count(v[1]), count(v[2]), v[3],
                           count(v[4]), count(v[5]), v[6],        count(v[7])};
  }
}

} // namespace yuxi
