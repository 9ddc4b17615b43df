// A simulation's saved state: saving this rank's section (save_state), and continuing from a
// checkpoint's sections on as many ranks as wrote it or on another number, or under another
// scene (a branch), in a simulation built straight from them or in place (load); taking the
// state of another engine that advanced the run (take_engine_state); gathering the particles
// onto one rank.
//
// A section, in order: time, step, the cumulative books, the count of list builds, the initial
// balance, the last tally; the walls' section (Walls::save); the sources' (Sources::save); the
// three axes' cut planes; the cells' edge and the skin (layout 9); the owned particles
// (ParticleStore::checkpoint); the contacts' states (ContactStates::save). Reading a section
// fills the parts and builds nothing; the continuation then lays out the ranks and cells and
// makes the list build explicitly.
#include "core/archive.hpp"
#include "sim/cell_sizing.hpp"
#include "sim/contact_reach.hpp"
#include "sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace yuxi {

void Simulation::save_state(ArchiveWriter& ar) const {
  ar.value(time_);
  ar.value(step_);
  ar.value(ledger_.books());
  ar.value(list_builds_);
  ar.value(ledger_.initial_balance());
  ar.value(contacts_.tally());
  walls_.save(ar);
  sources_.save(ar);
  for (const std::vector<double>& cuts : exchange_.cuts()) ar.vector(cuts);
  ar.value(exchange_.cell_edge());
  ar.value(config_.skin);
  clumps_.save(ar);
  ar.value(static_cast<std::uint64_t>(shape_names_.size()));
  for (const std::string& name : shape_names_) ar.string(name);
  store_.save(ar);
  contacts_.history().save(ar, store_, search_.list());
}

Simulation::SavedCells Simulation::read_section(ArchiveReader& ar, const SectionPlan& plan) {
  ar.value(time_);
  ar.value(step_);
  ar.value(ledger_.books());
  ar.value(list_builds_);
  double initial_balance = 0.0;
  ar.value(initial_balance);
  ledger_.set_initial_balance(initial_balance);
  ar.value(contacts_.tally());
  walls_.load(ar, plan.layout);
  sources_.load(ar, plan.layout);
  SavedCells cells;
  for (std::vector<double>& axis : cells.cuts) ar.vector(axis);
  if (plan.layout >= 9) {
    ar.value(cells.edge);
    ar.value(cells.skin);
    if (!(cells.edge > 0.0 && std::isfinite(cells.edge) && cells.skin >= 0.0 &&
          cells.skin < cells.edge))
      throw ArchiveError("the cells' edge or the skin is impossible (corrupt)");
  }
  if (plan.layout >= 10) {
    clumps_.load(ar);
    // The names the clumps' shapes had (layout 12; before, taken to be this scene's).
    std::vector<std::string> saved = shape_names_;
    if (plan.layout >= 12) {
      std::uint64_t n = 0;
      ar.value(n);
      ar.check_room(n, sizeof n);
      saved.resize(n);
      for (std::string& name : saved) ar.string(name);
    }
    clumps_.rename_shapes(saved, shape_names_);
  } else {
    clumps_.set({});
  }
  store_.clear_ghosts();
  store_.checkpoint(ar, plan.layout >= 10);
  if (plan.keep_history) {
    contacts_.history().load(ar);
  } else {
    contacts_.history().forget();
    ar.skip_to_end();
  }
  return cells;
}

void Simulation::validate_loaded_particles() const {
  // The checksum guards against damage; this guards the engine against a checkpoint that is
  // intact but does not belong to this scene (or was crafted): nothing loaded may index out of
  // range or start the run with impossible values.
  const std::size_t n_materials = contacts_.n_materials();
  const std::size_t n_motions = walls_.motions().size();
  for (std::size_t i = 0; i < store_.n_owned(); ++i) {
    const bool ok = (store_.kind[i] == Kind::grain || store_.kind[i] == Kind::wall) &&
                    store_.material[i] < n_materials && store_.motion[i] < n_motions &&
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
  const ContactTally& tally = contacts_.tally();
  const EnergyBooks& books = ledger_.books();
  const double scalars[] = {time_, ledger_.initial_balance(), tally.elastic, tally.relaxation};
  for (double x : scalars)
    if (!std::isfinite(x)) throw std::invalid_argument("the checkpoint holds a non-finite energy");
  if (!books.finite()) throw std::invalid_argument("the checkpoint holds a non-finite energy");
  constexpr std::size_t limit = std::size_t{1} << 48;
  if (step_ < 0 || list_builds_ < 0 || books.escaped > limit || tally.touching > limit)
    throw std::invalid_argument("the checkpoint holds an impossible step or count");
}

Simulation::Simulation(SimulationFrame frame, const SavedState& saved, Comm comm,
                       std::optional<BranchCheck> branch)
    : config_(std::move(frame.config)),
      // (laid out for the particles once they are read: lay_out_for_loaded)
      exchange_(config_.box, comm, config_.ranks, Vec3{},
                std::max({config_.box.length(0), config_.box.length(1), config_.box.length(2)})),
      search_(config_.skin, config_.box), contacts_(std::move(frame.law), config_.backend),
      walls_(config_, std::move(frame.planes), std::move(frame.motions),
             std::move(frame.shaped_walls)) {
  if (!(config_.dt > 0.0)) throw std::invalid_argument("time step must be positive");
  if (!frame.inserts.empty() || !frame.outlets.empty())
    sources_.set(std::move(frame.inserts), std::move(frame.outlets));
  shape_names_ = std::move(frame.shape_names);
  continue_from(saved, branch ? &*branch : nullptr);
}

void Simulation::load(const SavedState& saved) {
  ++edits_;
  continue_from(saved, nullptr);
}

void Simulation::lay_out_for_loaded(const SavedCells& cells, bool own) {
  const Comm& c = comm();
  // The same on every rank: the saved run's cells (every section holds them; a rank may load
  // none), the largest contact distance of the particles, and the saved layout.
  double agreed[5] = {cells.edge, cells.skin, contact_reach(store_), 0.0, 0.0};
  std::array<int, 3> layout = config_.ranks;
  if (own) {
    for (int a = 0; a < 3; ++a) layout[a] = static_cast<int>(cells.cuts[a].size()) - 1;
    agreed[3] = layout[0] + 1e3 * layout[1] + 1e6 * layout[2];
    agreed[4] = -agreed[3];
  }
  c.max(agreed, 5);
  const double reach = agreed[2];
  if (own && (agreed[3] != -agreed[4] || layout[0] * layout[1] * layout[2] != c.size() ||
              std::min({layout[0], layout[1], layout[2]}) < 1))
    throw std::invalid_argument(
        fmt::format("the checkpoint's cut planes are not those of a layout of {} ranks", c.size()));
  double edge = agreed[0];
  if (edge > 0.0) { // the saved run's cells and skin
    // They are this scene's: at least what the scene sizes for the particles loaded (grains
    // only leave, or come no larger than its inserts' and the cells' allow), with no larger a
    // skin. (A state that claims smaller cells was written by another scene, or crafted: its
    // grid could run to billions of cells.)
    SimulationConfig scene = config_;
    const double least = cell_edge_for(scene, reach);
    if (!(edge >= least * (1.0 - 1e-12)) || !(agreed[1] <= config_.skin))
      throw std::invalid_argument(fmt::format(
          "the checkpoint's cells (edge {}, skin {}) are not this scene's (edge at least {}, "
          "skin at most {})",
          edge, agreed[1], least, config_.skin));
    config_.skin = agreed[1];
  } else { // for the particles loaded, with this scene's skin (a branch, an older layout)
    edge = cell_edge_for(config_, reach);
  }
  if (reach > edge + 1e-12)
    throw std::invalid_argument("the checkpoint's particles are larger than this scene's cells");
  search_ = NeighborSearch(config_.skin, config_.box);
  walls_.size_for(config_.skin, edge);
  if (own) {
    // The cells of the saved sub-domain: the list build then sorts and bins as the saved run.
    exchange_.lay_out(layout, Vec3{}, edge);
    exchange_.set_cuts(cells.cuts);
  } else {
    // This run's own decomposition, cut by particle count; the list build's migration then
    // takes every particle to its owner.
    exchange_.lay_out(config_.ranks, occupied_lengths(config_.box, store_, &c), edge);
    exchange_.cut_by_count(store_);
  }
}

void Simulation::evaluate_branched_forces() {
  // The saved state's books (the saved contact law's stored energy), then the same state's
  // under this scene: the difference comes from outside the equations of motion.
  const EnergyBooks before = energies();
  start_forces_from_gravity();
  compute_forces(false);
  stop_if_unhealthy();
  const EnergyBooks after = energies();
  if (comm().root())
    ledger_.books().inserted +=
        (after.mechanical() + after.relaxation) - (before.mechanical() + before.relaxation);
}

void Simulation::continue_from(const SavedState& saved, const BranchCheck* branch) {
  const Comm& c = comm();
  // (a branch takes its shares as on another number of ranks: merged, cut afresh)
  const bool own = !branch && saved.written_on == static_cast<std::uint64_t>(c.size());
  // Every rank learns whether every other loaded its share before any takes a collective step.
  std::string error;
  SavedCells cells;
  try {
    if (saved.written_on == 0) throw ArchiveError("no rank's state in the file");
    if (own && saved.share.size() != 1) throw ArchiveError("no state for this rank in the file");
    if (own)
      cells = read_own_section(saved.share.front(), saved.layout);
    else
      cells = merge_sections(saved.share, {saved.layout, !branch || branch->keep_history});
    // (a branch sizes the cells for its own skin)
    if (branch) cells.edge = 0.0;
    validate_loaded_particles();
    clumps_.index_members(store_); // (every member there, each naming a clump that is)
  } catch (const ArchiveError& e) {
    error = e.what();
  } catch (const std::length_error&) {
    error = "a size field is impossible (corrupt)";
  } catch (const std::invalid_argument& e) { // the loaded particles do not fit the scene
    error = e.what();
  }
  error = c.first_error(error);
  if (!error.empty()) throw std::invalid_argument(error);
  update_clump_reach(); // (before the ranks are laid out: their least width)
  lay_out_for_loaded(cells, own);
  // (a state of an older layout holds no next id)
  GlobalId top = -1;
  for (std::size_t i = 0; i < store_.n_owned(); ++i) top = std::max(top, store_.gid[i]);
  sources_.ids_from(static_cast<GlobalId>(c.max(static_cast<double>(top))) + 1);
  if (own) {
    build_lists_after_load(true);
    return;
  }
  // The run's scalars, the same in every section, from the ranks that loaded one (a rank's
  // share may be empty), and the books summed over the sections, onto rank 0.
  const bool loaded = !saved.share.empty();
  double scalars[] = {loaded ? time_ : -HUGE_VAL, loaded ? static_cast<double>(step_) : -HUGE_VAL,
                      loaded ? static_cast<double>(list_builds_) : -HUGE_VAL,
                      loaded ? ledger_.initial_balance() : -HUGE_VAL};
  c.max(scalars, 4);
  time_ = scalars[0];
  step_ = static_cast<std::int64_t>(scalars[1]);
  list_builds_ = static_cast<std::int64_t>(scalars[2]);
  ledger_.set_initial_balance(scalars[3]);
  // The inserts' progress and the next id, the same in every section, from those that loaded.
  sources_.agree_over(c, loaded);
  EnergyBooks& books = ledger_.books();
  books.sum_over(c);
  ContactTally& tally = contacts_.tally();
  double sums[] = {tally.elastic, tally.relaxation, static_cast<double>(tally.touching)};
  c.sum(sums, 3);
  const bool root = c.root();
  walls_.sum_work_onto_root(c);
  if (!root) books = EnergyBooks{};
  tally = ContactTally{};
  if (root) {
    tally.elastic = sums[0];
    tally.relaxation = sums[1];
    tally.touching = static_cast<std::size_t>(sums[2]);
  }
  if (branch) {
    check_branched_particles(*branch);
    // The step count of this scene's time step; the walls where its motions put them.
    step_ = std::llround(time_ / config_.dt);
    walls_.place(store_, time_, true);
  }
  build_lists_after_load(false);
  if (branch) evaluate_branched_forces();
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
  const Comm& c = comm();
  const auto walls = static_cast<std::size_t>(c.sum(static_cast<double>(wall_particles)));
  // The grains are the checkpoint's, whatever the scene builds (its fills and particles give
  // way to them, and the ids of grains poured later follow the saved run's); the walls must be
  // the scene's, whose motions move them.
  std::string error = c.first_error(outside);
  if (error.empty() && walls != check.walls)
    error = fmt::format("the checkpoint holds {} wall particles, this scene builds {}: the "
                        "branch must keep the walls of the run it starts from",
                        walls, check.walls);
  if (!error.empty()) throw std::invalid_argument(error);
}

Simulation::SavedCells Simulation::read_own_section(const std::string& section,
                                                    std::uint32_t layout) {
  ArchiveReader ar(section);
  const SavedCells cells = read_section(ar, {layout, true});
  if (!ar.at_end()) throw ArchiveError("unread data after the state");
  return cells;
}

Simulation::SavedCells Simulation::merge_sections(const std::vector<std::string>& share,
                                                  const SectionPlan& plan) {
  SavedCells cells;
  ParticleStore pool;
  std::string states;
  EnergyBooks books;
  Walls::Work work{{}, std::vector<double>(walls_.planes().size(), 0.0)};
  Sources::OutletParts outlets;
  ContactTally tally;
  double time = 0, initial_balance = 0;
  std::int64_t step = 0, list_builds = 0;
  std::vector<ClumpBody> bodies;
  for (std::size_t k = 0; k < share.size(); ++k) {
    ArchiveReader ar(share[k]);
    const SavedCells read = read_section(ar, plan);
    if (k == 0) cells = read;
    if (!ar.at_end()) throw ArchiveError("unread data after a section");
    if (k == 0)
      time = time_, step = step_, list_builds = list_builds_,
      initial_balance = ledger_.initial_balance();
    for (std::size_t i = 0; i < store_.n_owned(); ++i) pool.append_copy(store_, i);
    bodies.insert(bodies.end(), clumps_.bodies().begin(), clumps_.bodies().end());
    states += contacts_.history().stashed_bytes();
    books.add(ledger_.books());
    const Walls::Work& w = walls_.work();
    work.shaped.resize(w.shaped.size(), 0.0);
    for (std::size_t s = 0; s < w.shaped.size(); ++s) work.shaped[s] += w.shaped[s];
    for (std::size_t p = 0; p < work.planes.size() && p < w.planes.size(); ++p)
      work.planes[p] += w.planes[p];
    sources_.add_outlet_parts(outlets);
    const ContactTally& t = contacts_.tally();
    tally.elastic += t.elastic;
    tally.relaxation += t.relaxation;
    tally.touching += t.touching;
  }
  store_ = std::move(pool);
  std::sort(bodies.begin(), bodies.end(),
            [](const ClumpBody& a, const ClumpBody& b) { return a.id < b.id; });
  clumps_.set(std::move(bodies));
  contacts_.history().give(states);
  time_ = time, step_ = step, list_builds_ = list_builds;
  ledger_.set_initial_balance(initial_balance);
  ledger_.books() = books;
  walls_.set_work(std::move(work));
  sources_.set_outlet_parts(outlets);
  contacts_.tally() = tally;
  return cells;
}

void Simulation::build_lists_after_load(bool as_saved) {
  // The history comes from the checkpoint's stash; the count of list builds is the saved run's.
  const auto counted = list_builds_;
  if (!as_saved) {
    build_lists({ListBuildPlan::After::load}); // (other ranks' sections: a new list)
  } else {
    // A state saved at any step: its particles stand in the order of the run's last list
    // build, and x_build holds where each stood then. Built from those positions, the list,
    // the ghosts and the owners are that build's again; then every particle goes back to where
    // it stands now, and the ghosts follow. The run goes on bit for bit as if never stopped,
    // whatever step it was saved at (a checkpoint leaves the trajectory untouched).
    // The shaped walls likewise stand where they stood at that build while it is made again.
    const Walls::AsBuilt as_built = walls_.stand_as_built();
    std::swap(store_.x, store_.x_build);
    build_lists({ListBuildPlan::After::load_at_last_build});
    std::swap(store_.x, store_.x_build);
    walls_.stand_again(as_built, time_);
    exchange_.forward(store_);
  }
  list_builds_ = counted;
}

void Simulation::take_engine_state(const EngineState& state) {
  if (comm().size() != 1)
    throw std::logic_error("take_engine_state: another engine's state is taken in one process");
  const std::size_t n = state.gid.size();
  const auto sizes_agree = [n](const auto&... field) { return ((field.size() == n) && ...); };
  if (!sizes_agree(state.x, state.x_build, state.v, state.w, state.f, state.torque) ||
      !std::is_sorted(state.gid.begin(), state.gid.end()))
    throw std::invalid_argument("take_engine_state: the state's fields are not one per particle "
                                "in ascending global id");
  // The particles that left (removed on escape) go; the others stand in global-id order.
  store_.clear_ghosts();
  std::vector<std::size_t> gone;
  for (std::size_t i = 0; i < store_.n_owned(); ++i)
    if (!std::binary_search(state.gid.begin(), state.gid.end(), store_.gid[i])) gone.push_back(i);
  store_.remove_owned(gone);
  std::vector<std::uint32_t> order(store_.n_owned());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return store_.gid[a] < store_.gid[b]; });
  store_.permute_owned(order);
  if (store_.n_owned() != n || !std::equal(state.gid.begin(), state.gid.end(), store_.gid.begin()))
    throw std::invalid_argument("take_engine_state: the state holds a particle that this "
                                "simulation does not");
  store_.x = state.x;
  store_.x_build = state.x_build;
  store_.v = state.v;
  store_.w = state.w;
  store_.f = state.f;
  store_.torque = state.torque;
  take_clump_motion(state.clumps);
  time_ = state.time;
  step_ = state.step;
  list_builds_ = state.list_builds;
  EnergyBooks& books = ledger_.books();
  books.dissipated = state.books.dissipated;
  books.wall_work = state.books.wall_work;
  books.removed = state.books.removed;
  books.gravity_work = state.books.gravity_work;
  books.inserted = state.books.inserted;
  books.escaped = state.books.escaped;
  ContactTally& tally = contacts_.tally();
  tally = ContactTally{};
  tally.elastic = state.elastic;
  tally.relaxation = state.relaxation;
  tally.touching = state.touching;
  contacts_.set_plane_loads(state.plane_loads);
  if (state.plane_work.size() == walls_.planes().size()) {
    Walls::Work work = walls_.work();
    work.planes = state.plane_work;
    walls_.set_work(std::move(work));
  }
  contacts_.history().forget();
  contacts_.history().give(state.contact_stash);
  // (the other engine records no contacts' forces: none is kept that would not match the list)
  contacts_.record_contacts(false);
  build_lists_after_load(true);
  // The books' check that the CPU engine makes after its list builds: a run that gains energy
  // that nothing put in (a time step too large, non-finite values) stops with its diagnosis.
  check_energy_books(energies());
}

void Simulation::take_clump_motion(const std::vector<EngineState::ClumpMotion>& motion) {
  std::vector<ClumpBody> kept;
  std::size_t next = 0;
  for (const ClumpBody& b : clumps_.bodies()) {
    if (next < motion.size() && motion[next].id < b.id) break;      // (one this simulation lacks)
    if (next == motion.size() || motion[next].id != b.id) continue; // (it left on escape)
    ClumpBody& taken = kept.emplace_back(b);
    const EngineState::ClumpMotion& m = motion[next++];
    taken.x = m.x;
    taken.v = m.v;
    taken.q = m.q;
    taken.p = m.p;
    taken.force = m.force;
    taken.torque = m.torque;
  }
  if (next != motion.size())
    throw std::invalid_argument(fmt::format(
        "take_engine_state: the state holds clump {}, which this simulation does not (or not "
        "in ascending id)",
        motion[next].id));
  clumps_.set(std::move(kept)); // (the members are found again at the list build that follows)
}

ParticleStore Simulation::gather_particles() const {
  ArchiveWriter out;
  ParticleStore mine = store_; // owned only, for the archive
  mine.clear_ghosts();
  mine.save(out);
  const auto parts = comm().gather(out.data());
  ParticleStore all;
  if (!comm().root()) return all;
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
