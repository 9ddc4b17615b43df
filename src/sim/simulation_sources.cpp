// Grains poured in ([[insert]]) and taken out ([[outlet]]) while a run goes on
// (scene/particle_source.hpp). Both happen at list builds, where particles may be added and
// removed: a batch due forces a list build at its step.
#include "scene/ball_hash.hpp"
#include "sim/simulation.hpp"

#include <cmath>
#include <fmt/format.h>

namespace yuxi {
namespace {

// The random stream of one batch of an insert: the same candidates on every number of ranks,
// and a resumed run draws the batches it has not drawn yet.
Random batch_stream(std::uint64_t seed, std::int64_t batch) {
  return Random(seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(batch) + 1);
}

} // namespace

void Simulation::set_sources(std::vector<InsertSpec> inserts, std::vector<OutletSpec> outlets) {
  inserts_ = std::move(inserts);
  outlets_ = std::move(outlets);
  insert_progress_.assign(inserts_.size(), InsertProgress{});
  for (std::size_t k = 0; k < inserts_.size(); ++k)
    if (inserts_[k].held) insert_progress_[k].halted = 1; // (until start_insert)
  outlet_part_.assign(outlets_.size(), OutletPart{});
}

Simulation::BatchSteps Simulation::batch_steps(std::size_t k) const {
  const InsertSpec& s = inserts_[k];
  const double dt = config_.dt;
  const std::int64_t first = insert_progress_[k].first_step >= 0
                                 ? insert_progress_[k].first_step
                                 : std::max<std::int64_t>(1, std::llround(s.start / dt));
  const std::int64_t every = std::max<std::int64_t>(1, std::llround(s.interval / dt));
  const std::int64_t last =
      std::isfinite(s.end) ? std::llround(s.end / dt) : std::numeric_limits<std::int64_t>::max();
  return {first, every, last};
}

bool Simulation::batch_due(std::size_t k, std::int64_t step) const {
  const InsertProgress& p = insert_progress_[k];
  const bool full = inserts_[k].total >= 0 && p.grains >= inserts_[k].total;
  const BatchSteps b = batch_steps(k);
  return p.halted == 0 && !full && step >= b.first && step <= b.last &&
         (step - b.first) % b.every == 0;
}

bool Simulation::insertion_due(std::int64_t step) const {
  for (std::size_t k = 0; k < inserts_.size(); ++k)
    if (batch_due(k, step)) return true;
  return false;
}

void Simulation::insert_due_batches() {
  for (std::size_t k = 0; k < inserts_.size(); ++k)
    if (batch_due(k, step_)) insert_batch(k);
}

void Simulation::adopt_sources(const std::vector<std::string>& insert_names,
                               const std::vector<InsertProgress>& inserts,
                               const std::vector<std::string>& outlet_names,
                               const std::vector<OutletPart>& outlets) {
  // (a handful of sources: a search by name each)
  std::vector<InsertProgress> progress(inserts_.size());
  for (std::size_t k = 0; k < inserts_.size(); ++k) {
    if (inserts_[k].held) progress[k].halted = 1;
    for (std::size_t j = 0; j < insert_names.size(); ++j)
      if (insert_names[j] == inserts_[k].name) progress[k] = inserts[j];
  }
  std::vector<OutletPart> parts(outlets_.size());
  for (std::size_t k = 0; k < outlets_.size(); ++k)
    for (std::size_t j = 0; j < outlet_names.size(); ++j)
      if (outlet_names[j] == outlets_[k].name) parts[k] = outlets[j];
  insert_progress_ = std::move(progress);
  outlet_part_ = std::move(parts);
}

void Simulation::start_insert(std::size_t k) {
  const InsertSpec& s = inserts_.at(k);
  InsertProgress& p = insert_progress_.at(k);
  if (p.halted == 2)
    throw std::invalid_argument(fmt::format("insert '{}' was stopped for good", s.name));
  if (s.total >= 0 && p.grains >= s.total)
    throw std::invalid_argument(
        fmt::format("insert '{}' has poured its total of {} grains", s.name, s.total));
  if (std::isfinite(s.end) && step_ + 1 > std::llround(s.end / config_.dt))
    throw std::invalid_argument(
        fmt::format("insert '{}' ends at t = {}, which has passed", s.name, s.end));
  p.first_step = step_ + 1;
  p.grains_before = p.grains;
  p.mass_before = p.mass;
  p.halted = 0;
}

void Simulation::pause_insert(std::size_t k) {
  if (insert_progress_.at(k).halted == 2)
    throw std::invalid_argument(fmt::format("insert '{}' was stopped for good", inserts_[k].name));
  insert_progress_[k].halted = 1;
}

void Simulation::stop_insert(std::size_t k) {
  insert_progress_.at(k).halted = 2;
}

void Simulation::add_insert(InsertSpec insert) {
  for (const InsertSpec& s : inserts_)
    if (s.name == insert.name)
      throw std::invalid_argument(fmt::format("an insert named '{}' exists already", s.name));
  const double r = insert.grains.size.largest();
  if (2 * r + config_.skin > cell_edge_)
    throw std::invalid_argument(fmt::format(
        "insert '{}': grains of radius {} are larger than the linked cells allow ({}); the scene "
        "must pour grains that large from the start",
        insert.name, r, 0.5 * (cell_edge_ - config_.skin)));
  const auto k = insert.grains.material;
  if (k >= n_materials_)
    throw std::invalid_argument(fmt::format("insert '{}': material {} is not one of the scene's {}",
                                            insert.name, k, n_materials_));
  std::string error;
  try {
    check_pairs_for(k, fmt::format("insert '{}'", insert.name));
  } catch (const std::invalid_argument& e) {
    error = e.what();
  }
  error = comm_.first_error(error);
  if (!error.empty()) throw std::invalid_argument(error);
  InsertProgress p;
  if (insert.held) p.halted = 1;
  p.first_step =
      std::max(step_ + 1, std::max<std::int64_t>(1, std::llround(insert.start / config_.dt)));
  inserts_.push_back(std::move(insert));
  insert_progress_.push_back(p);
}

void Simulation::insert_batch(std::size_t source) {
  const InsertSpec& s = inserts_[source];
  InsertProgress& progress = insert_progress_[source];
  const double dt = config_.dt;
  const BatchSteps b = batch_steps(source);
  // What is due by the end of this batch's interval, from the pouring under way: a count, or
  // grains until the mass is.
  const double elapsed = static_cast<double>(step_ - b.first + b.every) * dt;
  Random rng = batch_stream(s.grains.seed, progress.batches);
  ++progress.batches;
  struct Due {
    double radius;
    Vec3 velocity;
  };
  std::vector<Due> due;
  if (s.by_mass) {
    double mass = progress.mass;
    while (mass < progress.mass_before + s.rate * elapsed && due.size() < 1000000) {
      const double r = s.grains.size.draw(rng);
      due.push_back({r, s.grains.draw_velocity(rng)});
      mass += s.grains.mass_of(r);
    }
  } else {
    auto target =
        progress.grains_before + static_cast<std::int64_t>(std::floor(s.rate * elapsed + 1e-9));
    if (s.total >= 0) target = std::min(target, s.total);
    for (std::int64_t n = progress.grains; n < target; ++n) {
      const double r = s.grains.size.draw(rng);
      due.push_back({r, s.grains.draw_velocity(rng)});
    }
  }
  if (due.empty()) return;
  // Candidate places: `attempts` for each due grain, from the batch's stream.
  const std::size_t attempts = static_cast<std::size_t>(std::max(1, s.attempts));
  std::vector<Vec3> places(due.size() * attempts);
  for (auto& p : places) p = s.region.sample(rng, config_.box).value_or(Vec3{NAN, NAN, NAN});
  // Refused where the ball leaves the region or the domain, meets a flat wall, or overlaps a
  // particle this rank owns; every rank judges its own particles, and the refusals are
  // combined (max) so that every rank takes the same candidates. Positions are wrapped, and a
  // ball near a periodic face is looked for at its images across it too.
  const Box& box = config_.box;
  double r_max = s.grains.size.largest();
  std::vector<double> refused(places.size(), 0.0);
  Vec3 lo, hi;
  s.region.bounds_in(box, lo, hi);
  double reach = 2.0 * r_max;
  for (std::size_t i = 0; i < store_.n_owned(); ++i)
    reach = std::max(reach, store_.radius[i] + r_max);
  BallHash near(reach);
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    const Vec3 x = box.wrap(store_.x[i]);
    bool is_near = true; // (any distance along a periodic axis: an image may come near)
    for (int a = 0; a < 3; ++a)
      is_near = is_near && (box.periodic(a) || (x[a] >= lo[a] - reach && x[a] <= hi[a] + reach));
    if (is_near) near.add(x, store_.radius[i]);
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
    for (const PlaneWall& w : planes_) bad = bad || w.distance(x, time_) < r;
    refused[c] = bad ? 1.0 : 0.0;
  }
  if (comm_.size() > 1) comm_.max(refused.data(), static_cast<int>(refused.size()));
  // The same choice on every rank: for each due grain its first free place, clear of the
  // grains taken before it in this batch.
  BallHash taken(2.0 * r_max);
  const Vec3 g = potential_gravity();
  store_.clear_ghosts();
  std::int64_t placed = 0;
  for (std::size_t j = 0; j < due.size(); ++j) {
    for (std::size_t a = 0; a < attempts; ++a) {
      const std::size_t c = j * attempts + a;
      const Vec3& x = places[c];
      if (refused[c] > 0.0 || overlaps(taken, x, due[j].radius)) continue;
      taken.add(x, due[j].radius);
      const GlobalId id = next_gid_++;
      const double m = s.grains.mass_of(due[j].radius);
      ++placed;
      progress.mass += m;
      if (decomp_.owns(config_.box.wrap(x))) {
        ParticleSpec p;
        p.position = x;
        p.radius = due[j].radius;
        p.mass = m;
        p.material = s.grains.material;
        // The step's second half kick (gravity alone, until its contacts are computed) brings
        // the velocity to the one drawn: it starts half a kick behind.
        p.velocity = due[j].velocity - (0.5 * dt) * config_.gravity;
        const std::size_t i = store_.add(p, id);
        store_.f[i] = m * config_.gravity;
        // Its kinetic and potential energy come from outside the equations of motion.
        books_.inserted += 0.5 * m * norm2(due[j].velocity) - m * dot(g, x);
      }
      break;
    }
  }
  progress.grains += placed;
  progress.owed = static_cast<std::int64_t>(due.size()) - placed;
}

void Simulation::handle_outlets() {
  std::vector<std::size_t> gone;
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    if (!store_.is_grain(i)) continue;
    for (std::size_t k = 0; k < outlets_.size(); ++k)
      if (outlets_[k].region.contains(config_.box.wrap(store_.x[i]))) {
        gone.push_back(i);
        books_.removed += mechanical_energy(i);
        ++outlet_part_[k].grains;
        outlet_part_[k].mass += store_.mass[i];
        break;
      }
  }
  if (!gone.empty()) store_.remove_owned(gone);
}

std::vector<Simulation::SourceTally> Simulation::inflow() const {
  std::vector<SourceTally> out;
  for (std::size_t k = 0; k < inserts_.size(); ++k)
    out.push_back({inserts_[k].name, insert_progress_[k].grains, insert_progress_[k].mass,
                   insert_progress_[k].owed});
  return out;
}

std::vector<Simulation::SourceTally> Simulation::outflow() const {
  std::vector<double> sums;
  for (const OutletPart& p : outlet_part_)
    sums.insert(sums.end(), {static_cast<double>(p.grains), p.mass});
  if (!sums.empty()) comm_.sum(sums.data(), static_cast<int>(sums.size()));
  std::vector<SourceTally> out;
  for (std::size_t k = 0; k < outlets_.size(); ++k)
    out.push_back({outlets_[k].name, std::llround(sums[2 * k]), sums[2 * k + 1], 0});
  return out;
}

} // namespace yuxi
