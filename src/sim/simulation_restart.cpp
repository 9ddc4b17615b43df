// Loading a simulation's saved state (Simulation::checkpoint saves it), on as many ranks as
// wrote it or on another number, and gathering the particles onto one rank.
#include "core/archive.hpp"
#include "sim/contact_reach.hpp"
#include "sim/simulation.hpp"

#include <fmt/format.h>
#include <utility>

namespace yuxi {

void Simulation::validate_loaded_particles() const {
  // The checksum guards against damage; this guards the engine against a checkpoint that is
  // intact but does not belong to this scene (or was crafted): nothing loaded may index out of
  // range or start the run with impossible values.
  const std::size_t n_materials = n_materials_;
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    const bool ok = (store_.kind[i] == Kind::grain || store_.kind[i] == Kind::wall) &&
                    store_.material[i] < n_materials && store_.motion[i] < motions_.size() &&
                    store_.radius[i] > 0 && store_.mass[i] > 0 && std::isfinite(store_.radius[i]) &&
                    std::isfinite(store_.mass[i]) && is_finite(store_.x[i]) &&
                    is_finite(store_.v[i]) && is_finite(store_.w[i]) &&
                    std::isfinite(store_.inv_mass[i]) && std::isfinite(store_.inv_inertia[i]);
    if (!ok)
      throw std::invalid_argument(fmt::format(
          "particle {} of the checkpoint is invalid for this scene (kind, material, motion, "
          "radius, mass or a non-finite value)",
          i));
  }
  // The scalar state: finite energies and times, counts a run can have.
  const double scalars[] = {time_, initial_balance_, tally_.elastic, tally_.relaxation};
  for (double x : scalars)
    if (!std::isfinite(x)) throw std::invalid_argument("the checkpoint holds a non-finite energy");
  if (!books_.finite()) throw std::invalid_argument("the checkpoint holds a non-finite energy");
  constexpr std::size_t limit = std::size_t{1} << 48;
  if (step_ < 0 || rebuilds_ < 0 || books_.escaped > limit || tally_.touching > limit)
    throw std::invalid_argument("the checkpoint holds an impossible step or count");
  if (store_.radius.empty() ? false : contact_reach(store_) > grid_.edge().x + 1e-12)
    throw std::invalid_argument("the checkpoint's particles are larger than this scene's cells");
}

void Simulation::load(const std::vector<std::string>& share, std::uint64_t written_on,
                      std::uint32_t layout) {
  loading_layout_ = layout;
  // (a branch takes its shares as on another number of ranks: merged, cut afresh)
  const bool own = !branch_ && written_on == static_cast<std::uint64_t>(comm_.size());
  // Every rank learns whether every other loaded its share before any takes a collective step.
  std::string error;
  try {
    if (written_on == 0) throw ArchiveError("no rank's state in the file");
    if (own && share.size() != 1) throw ArchiveError("no state for this rank in the file");
    if (own)
      load_own_section(share.front());
    else
      merge_sections(share);
    validate_loaded_particles();
  } catch (const ArchiveError& e) {
    error = e.what();
  } catch (const std::length_error&) {
    error = "a size field is impossible (corrupt)";
  } catch (const std::invalid_argument& e) { // the loaded particles do not fit the scene
    error = e.what();
  }
  loading_ = Loading::whole;
  loading_layout_ = state_layout;
  error = comm_.first_error(error);
  if (!error.empty()) throw std::invalid_argument(error);
  // (a state of an older layout holds no next id)
  GlobalId top = -1;
  for (std::size_t i = 0; i < store_.n_owned(); ++i) top = std::max(top, store_.gid[i]);
  next_gid_ = std::max(next_gid_, static_cast<GlobalId>(comm_.max(static_cast<double>(top))) + 1);
  if (own) {
    rebuild_after_load(true);
    return;
  }
  // The run's scalars, the same in every section, from the ranks that loaded one (a rank's
  // share may be empty), and the books summed over the sections, onto rank 0.
  const bool loaded = !share.empty();
  double scalars[] = {loaded ? time_ : -HUGE_VAL, loaded ? static_cast<double>(step_) : -HUGE_VAL,
                      loaded ? static_cast<double>(rebuilds_) : -HUGE_VAL,
                      loaded ? initial_balance_ : -HUGE_VAL};
  comm_.max(scalars, 4);
  time_ = scalars[0];
  step_ = static_cast<std::int64_t>(scalars[1]);
  rebuilds_ = static_cast<std::int64_t>(scalars[2]);
  initial_balance_ = scalars[3];
  // The inserts' progress and the next id, the same in every section, from those that loaded.
  std::vector<double> sources{loaded ? static_cast<double>(next_gid_) : -HUGE_VAL};
  constexpr int fields = InsertProgress::n_numbers;
  for (const InsertProgress& p : insert_progress_)
    for (double v :
         {static_cast<double>(p.batches), static_cast<double>(p.grains),
          static_cast<double>(p.owed), p.mass, static_cast<double>(p.first_step),
          static_cast<double>(p.grains_before), p.mass_before, static_cast<double>(p.halted)})
      sources.push_back(loaded ? v : -HUGE_VAL);
  comm_.max(sources.data(), static_cast<int>(sources.size()));
  next_gid_ = static_cast<GlobalId>(sources[0]);
  const auto count = [](double v) { return static_cast<std::int64_t>(v); };
  for (std::size_t k = 0; k < insert_progress_.size(); ++k) {
    const double* v = &sources[1 + fields * k];
    insert_progress_[k] = {count(v[0]), count(v[1]), count(v[2]), v[3],
                           count(v[4]), count(v[5]), v[6],        count(v[7])};
  }
  books_.sum_over(comm_);
  double tally[] = {tally_.elastic, tally_.relaxation, static_cast<double>(tally_.touching)};
  comm_.sum(tally, 3);
  const bool root = comm_.root();
  wall_work_.resize(walls_.size(), 0.0);
  if (!wall_work_.empty()) comm_.sum(wall_work_.data(), static_cast<int>(wall_work_.size()));
  if (!root) std::fill(wall_work_.begin(), wall_work_.end(), 0.0);
  if (!root) books_ = EnergyBooks{};
  tally_ = ContactTally{};
  if (root) {
    tally_.elastic = tally[0];
    tally_.relaxation = tally[1];
    tally_.touching = static_cast<std::size_t>(tally[2]);
  }
  // This run's own decomposition, cut by particle count; the rebuild's migration then takes
  // every particle to its owner.
  cuts_moved_ = true;
  if (comm_.size() > 1)
    decomp_.balance(
        std::vector<Vec3>(store_.x.begin(),
                          store_.x.begin() + static_cast<std::ptrdiff_t>(store_.n_owned())),
        std::vector<double>(store_.n_owned(), 1.0), comm_);
  grid_ = CellGrid(decomp_.local_box(), cell_edge_);
  if (branch_) {
    check_branched_particles(*branch_);
    // The step count of this scene's time step; the walls where its motions put them.
    step_ = std::llround(time_ / config_.dt);
    place_walls(time_, true);
  }
  rebuild_after_load(false);
}

void Simulation::check_branched_particles(const BranchCheck& check) const {
  std::size_t wall_particles = 0;
  std::string outside;
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    wall_particles += store_.is_grain(i) ? 0 : 1;
    const Vec3 x = config_.box.wrap(store_.x[i]);
    if (outside.empty() && store_.is_grain(i) && !config_.box.contains(x))
      outside = fmt::format("grain {} of the checkpoint stands at ({:.6g}, {:.6g}, {:.6g}), "
                            "outside this scene's domain",
                            store_.gid[i], x.x, x.y, x.z);
  }
  const auto walls = static_cast<std::size_t>(comm_.sum(static_cast<double>(wall_particles)));
  // The grains are the checkpoint's, whatever the scene builds (its fills and particles give
  // way to them, and the ids of grains poured later follow the saved run's); the walls must be
  // the scene's, whose motions move them.
  std::string error = comm_.first_error(outside);
  if (error.empty() && walls != check.walls)
    error = fmt::format("the checkpoint holds {} wall particles, this scene builds {}: the "
                        "branch must keep the walls of the run it starts from",
                        walls, check.walls);
  if (!error.empty()) throw std::invalid_argument(error);
}

void Simulation::branch(const std::vector<std::string>& share, std::uint64_t written_on,
                        const BranchCheck& check, std::uint32_t layout) {
  branch_ = check;
  try {
    load(share, written_on, layout);
  } catch (...) {
    branch_.reset();
    throw;
  }
  branch_.reset();
  // The saved state's books (the saved contact law's stored energy), then the same state's
  // under this scene: the difference comes from outside the equations of motion.
  const EnergyBooks before = energies();
  start_forces_from_gravity();
  compute_forces(false);
  stop_if_unhealthy();
  const EnergyBooks after = energies();
  if (comm_.root())
    books_.inserted +=
        (after.mechanical() + after.relaxation) - (before.mechanical() + before.relaxation);
}

void Simulation::load_own_section(const std::string& section) {
  loading_ = Loading::deferred;
  ArchiveReader ar(section);
  checkpoint(ar);
  if (!ar.at_end()) throw ArchiveError("unread data after the state");
}

void Simulation::merge_sections(const std::vector<std::string>& share) {
  ParticleStore pool;
  std::string states;
  EnergyBooks books;
  std::vector<double> wall_work, plane_work(planes_.size(), 0.0);
  std::vector<OutletPart> outlets(outlet_part_.size());
  ContactTally tally;
  double time = 0, initial_balance = 0;
  std::int64_t step = 0, rebuilds = 0;
  loading_ = Loading::merged;
  for (std::size_t k = 0; k < share.size(); ++k) {
    ArchiveReader ar(share[k]);
    checkpoint(ar);
    if (!ar.at_end()) throw ArchiveError("unread data after a section");
    if (k == 0)
      time = time_, step = step_, rebuilds = rebuilds_, initial_balance = initial_balance_;
    for (std::size_t i = 0; i < store_.n_owned(); ++i) pool.append_copy(store_, i);
    states += history_->stashed_bytes();
    books.add(books_);
    wall_work.resize(wall_work_.size(), 0.0);
    for (std::size_t w = 0; w < wall_work_.size(); ++w) wall_work[w] += wall_work_[w];
    for (std::size_t p = 0; p < plane_work.size() && p < plane_work_.size(); ++p)
      plane_work[p] += plane_work_[p];
    for (std::size_t o = 0; o < outlets.size(); ++o) {
      outlets[o].grains += outlet_part_[o].grains;
      outlets[o].mass += outlet_part_[o].mass;
    }
    tally.elastic += tally_.elastic;
    tally.relaxation += tally_.relaxation;
    tally.touching += tally_.touching;
  }
  store_ = std::move(pool);
  history_->give(states);
  time_ = time, step_ = step, rebuilds_ = rebuilds, initial_balance_ = initial_balance;
  books_ = books;
  wall_work_ = wall_work;
  wall_work_.resize(walls_.size(), 0.0);
  outlet_part_ = outlets;
  plane_work_ = plane_work;
  tally_ = tally;
}

void Simulation::rebuild_after_load(bool as_saved) {
  // The history comes from the checkpoint's stash; the count of list builds is the saved run's.
  const auto counted = rebuilds_;
  if (!as_saved) {
    rebuild(BuildAfter::load); // (the particles of other ranks' sections: a new list)
  } else {
    // A state saved at any step: its particles stand in the order of the run's last list
    // build, and x_build holds where each stood then. Built from those positions, the list,
    // the ghosts and the owners are that build's again; then every particle goes back to where
    // it stands now, and the ghosts follow. The run goes on bit for bit as if never stopped,
    // whatever step it was saved at (a checkpoint leaves the trajectory untouched).
    // The meshes likewise stand where they stood at that build while it is made again, a
    // servo's where it had carried its mesh then.
    const double built = walls_built_at_;
    std::vector<double> servo_now;
    for (ShapedWall& w : walls_)
      if (auto* m = std::get_if<MeshWall>(&w))
        servo_now.push_back(std::exchange(m->servo_offset, m->servo_offset_built));
    place_shaped_walls(built, true);
    std::swap(store_.x, store_.x_build);
    rebuild(BuildAfter::load_at_last_build);
    std::swap(store_.x, store_.x_build);
    walls_built_at_ = built;
    std::size_t k = 0;
    for (ShapedWall& w : walls_)
      if (auto* m = std::get_if<MeshWall>(&w)) m->servo_offset = servo_now[k++];
    place_shaped_walls(time_, true);
    halo_.forward(store_, comm_);
  }
  rebuilds_ = counted;
}

ParticleStore Simulation::gather_particles() const {
  ArchiveWriter out;
  ParticleStore mine = store_; // owned only, for the archive
  mine.clear_ghosts();
  mine.checkpoint(out);
  const auto parts = comm_.gather(out.data());
  ParticleStore all;
  if (!comm_.root()) return all;
  std::vector<ParticleStore> stores(parts.size());
  std::vector<std::pair<GlobalId, std::pair<std::size_t, std::size_t>>> order;
  for (std::size_t r = 0; r < parts.size(); ++r) {
    ArchiveReader in(parts[r]);
    stores[r].checkpoint(in);
    for (std::size_t i = 0; i < stores[r].n_owned(); ++i)
      order.push_back({stores[r].gid[i], {r, i}});
  }
  std::sort(order.begin(), order.end());
  for (const auto& [gid, where] : order) all.append_copy(stores[where.first], where.second);
  return all;
}

} // namespace yuxi
