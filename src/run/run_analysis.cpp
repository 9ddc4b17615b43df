#include "run/run_analysis.hpp"

#include "analysis/analysis_csv.hpp"
#include "analysis/free_surface.hpp"
#include "analysis/grain_energy.hpp"
#include "analysis/velocity_section.hpp"
#include "core/archive.hpp"
#include "core/units.hpp"
#include "io/npy_records.hpp"
#include "run/particle_elastic_energy.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>

namespace yuxi {
namespace {

std::int64_t step_of(double t, double dt) {
  return std::llround(t / dt);
}

std::set<std::int64_t> steps_of(const std::vector<double>& times, double dt) {
  std::set<std::int64_t> out;
  for (double t : times) out.insert(step_of(t, dt));
  return out;
}

} // namespace

RunAnalysis::RunAnalysis(const Scene& scene, std::filesystem::path dir, double dt,
                         std::optional<std::int64_t> resume_after)
    : settings_(*scene.analysis), dir_(std::move(dir)),
      grid_(scene.sim.box.lo, scene.sim.box.hi, static_cast<std::size_t>(settings_.grid[0]),
            static_cast<std::size_t>(settings_.grid[1])),
      pdf_kinetic_(settings_.pdf_range[0], settings_.pdf_range[1], settings_.bins_per_decade),
      pdf_elastic_(settings_.pdf_range[0], settings_.pdf_range[1], settings_.bins_per_decade),
      pdf_total_(settings_.pdf_range[0], settings_.pdf_range[1], settings_.bins_per_decade),
      sections_(grid_, settings_.section_heights, settings_.section_width) {
  const auto& s = settings_;
  const Box& box = scene.sim.box;
  axis_ = 0.5 * (box.lo + box.hi);
  if (scene.basin) { // the basin's axis: the centre of its lattice
    const auto& b = *scene.basin;
    axis_ = {box.lo.x + 0.5 * b.cells[0] * b.spacing, box.lo.y + 0.5 * b.cells[1] * b.spacing, 0};
  }
  surface_steps_ = steps_of(s.surface_times, dt);
  velocity_steps_ = steps_of(s.velocity_times, dt);
  elastic_steps_ = steps_of(s.elastic_map_times, dt);
  period_first_ = step_of(s.period_start, dt);
  period_last_ = step_of(s.period_start + s.period_length, dt);
  period_every_ = std::max<std::int64_t>(1, step_of(s.sample_interval, dt));
  sectors_ = {axis_, s.mode, s.sector_half_width * pi / 180.0, s.r_max};
  const auto every = [&](double from, double until, double interval) {
    return Every{step_of(from, dt), step_of(until, dt),
                 interval > 0 ? std::max<std::int64_t>(1, step_of(interval, dt)) : 0};
  };
  track_ =
      every(s.period_start, s.track_until < 0 ? scene.run.t_end : s.track_until, s.track_interval);
  wave_ = every(s.period_start, s.wave_until, s.wave_interval);
  sample_ = every(s.grain_samples_from, s.grain_samples_until, s.grain_sample_interval);
  resume_after_ = resume_after;
  std::filesystem::create_directories(dir_ / "analysis");
  if (sample_.every > 0) std::filesystem::create_directories(dir_ / "analysis" / "grains");
}

bool RunAnalysis::period_sample(std::int64_t step) const {
  return step >= period_first_ && step <= period_last_ &&
         (step - period_first_) % period_every_ == 0;
}

bool RunAnalysis::needs_energies(std::int64_t step) const {
  return period_sample(step) || elastic_steps_.count(step) > 0 || wave_.due(step) ||
         sample_.due(step);
}

std::int64_t RunAnalysis::Every::next_after(std::int64_t step) const {
  constexpr std::int64_t none = std::numeric_limits<std::int64_t>::max();
  if (every <= 0) return none;
  const std::int64_t next = step < first ? first : first + ((step - first) / every + 1) * every;
  return next <= last ? next : none;
}

std::int64_t RunAnalysis::next_step_after(std::int64_t step) const {
  std::int64_t next = std::numeric_limits<std::int64_t>::max();
  for (const std::set<std::int64_t>* steps : {&surface_steps_, &velocity_steps_, &elastic_steps_})
    if (const auto it = steps->upper_bound(step); it != steps->end()) next = std::min(next, *it);
  const Every period{period_first_, period_last_, period_every_};
  for (const Every& e : {period, track_, wave_, sample_}) next = std::min(next, e.next_after(step));
  if (step < period_last_) next = std::min(next, period_last_);
  return next;
}

void RunAnalysis::set_elastic_energy(std::function<std::vector<double>(Simulation&)> source) {
  elastic_energy_ = std::move(source);
}

void RunAnalysis::before_step(Simulation& sim) const {
  sim.record_contacts(needs_energies(sim.step_count() + 1));
}

RunAnalysis::Grains RunAnalysis::grains(Simulation& sim, bool energies) const {
  const auto& p = sim.particles();
  Grains g;
  std::vector<double> elastic;
  if (energies) // collective
    elastic = elastic_energy_ ? elastic_energy_(sim) : particle_elastic_energy(sim);
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    if (!p.is_grain(i)) continue;
    g.x.push_back(p.x[i]);
    g.v.push_back(p.v[i]);
    g.radius.push_back(p.radius[i]);
    g.mass.push_back(p.mass[i]);
    g.id.push_back(p.gid[i]);
    if (energies) {
      g.kinetic.push_back(0.5 * p.mass[i] * norm2(p.v[i]) + sim.rotational_energy(i));
      g.elastic.push_back(elastic[i]);
    }
  }
  return g;
}

analysis::GridField RunAnalysis::surface(Simulation& sim, const Grains& g) const {
  analysis::GridField f = analysis::free_surface(grid_, g.x, g.radius);
  constexpr double none = -std::numeric_limits<double>::infinity();
  for (double& h : f.values)
    if (std::isnan(h)) h = none;
  sim.comm().max(f.values.data(), static_cast<int>(f.values.size()));
  for (double& h : f.values)
    if (h == none) h = std::numeric_limits<double>::quiet_NaN();
  return f;
}

analysis::GridField RunAnalysis::elastic_columns(Simulation& sim, const Grains& g) const {
  analysis::GridField f = analysis::column_sum(grid_, g.x, g.elastic);
  sim.comm().sum(f.values.data(), static_cast<int>(f.values.size()));
  return f;
}

void RunAnalysis::write_surface(Simulation& sim, const Grains& g) const {
  const analysis::GridField f = surface(sim, g);
  if (sim.comm().root())
    analysis::write_surface_csv(
        dir_ / "analysis" / analysis::timed_file_name("surface", sim.time()), f);
}

EnergyCsv& RunAnalysis::series(std::unique_ptr<EnergyCsv>& csv, const char* name,
                               const char* header) {
  if (!csv) csv = std::make_unique<EnergyCsv>(dir_ / "analysis" / name, resume_after_, header);
  return *csv;
}

void RunAnalysis::write_profiles(EnergyCsv& csv, const Simulation& sim,
                                 const analysis::GridField& f) const {
  for (const auto kind : {analysis::SectorKind::antinode, analysis::SectorKind::node}) {
    const auto p = analysis::radial_profile(f, sectors_, kind, settings_.profile_bin);
    for (std::size_t k = 0; k < p.count.size(); ++k)
      csv.write_row(fmt::format("{},{:.10g},{},{},{},{},{},{},{}", sim.step_count(), sim.time(),
                                kind == analysis::SectorKind::antinode ? "antinode" : "node",
                                analysis::csv_number(static_cast<double>(k) * p.dr),
                                analysis::csv_number(static_cast<double>(k + 1) * p.dr), p.count[k],
                                analysis::csv_number(p.mean[k]), analysis::csv_number(p.median[k]),
                                analysis::csv_number(p.max[k])));
  }
}

constexpr const char* profile_header = "step,time,direction,r_lo,r_hi,columns,mean,median,max";

void RunAnalysis::write_tracks(Simulation& sim, const Grains& g) {
  const analysis::GridField f = surface(sim, g);
  if (!sim.comm().root()) return;
  auto& peaks = series(peaks_, "peaks.csv", "step,time,sector,azimuth,r,height");
  for (const auto& p : analysis::sector_peaks(f, sectors_))
    peaks.write_row(fmt::format("{},{:.10g},{},{},{},{}", sim.step_count(), sim.time(), p.sector,
                                analysis::csv_number(p.azimuth), analysis::csv_number(p.r),
                                analysis::csv_number(p.value)));
  write_profiles(series(surface_profile_, "surface_profile.csv", profile_header), sim, f);
}

void RunAnalysis::write_waves(Simulation& sim, const Grains& g) {
  const analysis::GridField f = elastic_columns(sim, g);
  if (sim.comm().root())
    write_profiles(series(elastic_profile_, "elastic_profile.csv", profile_header), sim, f);
}

void RunAnalysis::write_grain_sample(Simulation& sim, const Grains& g) const {
  static const std::vector<NpyField> fields = {
      {"id", "<i8"},     {"x", "<f4"},    {"y", "<f4"},       {"z", "<f4"},
      {"radius", "<f4"}, {"mass", "<f4"}, {"kinetic", "<f8"}, {"elastic", "<f8"}};
  std::string records;
  records.reserve(g.x.size() * 40);
  const auto put = [&](auto value) {
    records.append(reinterpret_cast<const char*>(&value), sizeof value);
  };
  static_assert(std::endian::native == std::endian::little, ".npy records are little-endian");
  for (std::size_t k = 0; k < g.x.size(); ++k) {
    put(static_cast<std::int64_t>(g.id[k]));
    for (double v : {g.x[k].x, g.x[k].y, g.x[k].z, g.radius[k], g.mass[k]})
      put(static_cast<float>(v));
    put(g.kinetic[k]);
    put(g.elastic[k]);
  }
  write_npy_records(sim.comm(),
                    dir_ / "analysis" / "grains" /
                        analysis::timed_file_name("grains", sim.time(), 4, ".npy"),
                    fields, records);
}

void RunAnalysis::write_velocity_section(Simulation& sim, const Grains& g) const {
  const auto mine = analysis::velocity_section(g.x, g.v, axis_, settings_.section_azimuth,
                                               settings_.section_half_thickness);
  ArchiveWriter out; // the few grains in the plane travel to rank 0, with their ids
  std::vector<double> packed;
  for (const auto& p : mine.points)
    packed.insert(packed.end(), {static_cast<double>(g.id[p.index]), p.s, p.z, p.vs, p.vz, p.vn});
  out.vector(packed);
  const auto parts = sim.comm().gather(out.data());
  if (!sim.comm().root()) return;
  // In ascending grain id: the same rows whatever the ranks, or the engine, kept them in.
  std::vector<std::pair<double, analysis::SectionPoint>> by_id;
  for (const auto& part : parts) {
    ArchiveReader in(part);
    std::vector<double> v;
    in.vector(v);
    for (std::size_t k = 0; k + 5 < v.size(); k += 6)
      by_id.push_back({v[k], {0, v[k + 1], v[k + 2], v[k + 3], v[k + 4], v[k + 5]}});
  }
  std::sort(by_id.begin(), by_id.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  analysis::VelocitySection all = mine;
  all.points.clear();
  for (auto& [id, point] : by_id) {
    point.index = all.points.size();
    all.points.push_back(point);
  }
  analysis::write_velocity_section_csv(
      dir_ / "analysis" / analysis::timed_file_name("velocity", sim.time()), all);
}

void RunAnalysis::write_elastic_map(Simulation& sim, const Grains& g) const {
  const analysis::GridField f = elastic_columns(sim, g);
  if (sim.comm().root())
    analysis::write_column_sum_csv(
        dir_ / "analysis" / analysis::timed_file_name("elastic_map", sim.time(), 4), f, "elastic");
}

void RunAnalysis::accumulate_period(const Grains& g) {
  if (!sections_.empty()) sections_.add(g.x, g.kinetic, g.elastic);
  pdf_kinetic_.add(g.kinetic);
  pdf_elastic_.add(g.elastic);
  for (std::size_t i = 0; i < g.kinetic.size(); ++i) pdf_total_.add(g.kinetic[i] + g.elastic[i]);
}

void RunAnalysis::after_step(Simulation& sim) {
  const std::int64_t k = sim.step_count();
  const bool surface_map = surface_steps_.count(k) > 0, velocity = velocity_steps_.count(k) > 0;
  const bool energies = needs_energies(k);
  if (!surface_map && !velocity && !energies && !track_.due(k)) {
    if (k == period_last_) finish(sim);
    return;
  }
  const Grains g = grains(sim, energies);
  if (surface_map) write_surface(sim, g);
  if (velocity) write_velocity_section(sim, g);
  if (elastic_steps_.count(k) > 0) write_elastic_map(sim, g);
  if (track_.due(k)) write_tracks(sim, g);
  if (wave_.due(k)) write_waves(sim, g);
  if (sample_.due(k)) write_grain_sample(sim, g);
  if (period_sample(k)) accumulate_period(g);
  if (k == period_last_) finish(sim);
}

void RunAnalysis::finish(Simulation& sim) {
  if (finished_ || pdf_kinetic_.samples() == 0) return;
  finished_ = true;
  const auto sum = [&](double* values, int n) { sim.comm().sum(values, n); };
  sections_.combine(sum);
  pdf_kinetic_.combine(sum);
  pdf_elastic_.combine(sum);
  pdf_total_.combine(sum);
  if (!sim.comm().root()) return;
  const auto folder = dir_ / "analysis";
  if (!sections_.empty()) sections_.write_csv(folder / "period_sections.csv");
  std::vector<analysis::NamedFit> fits;
  const std::pair<const char*, const analysis::LogHistogram*> pdfs[] = {
      {"kinetic", &pdf_kinetic_}, {"elastic", &pdf_elastic_}, {"total", &pdf_total_}};
  for (const auto& [name, h] : pdfs) {
    const analysis::Density d = h->density();
    analysis::write_density_csv(folder / fmt::format("pdf_{}.csv", name), d);
    for (const auto& [range, r] :
         {std::pair{"A", settings_.fit_a}, std::pair{"B", settings_.fit_b}})
      fits.push_back({name, range, r[0], r[1], analysis::fit_power_law(d, r[0], r[1])});
  }
  analysis::write_fits_csv(folder / "fits.csv", fits);
}

} // namespace yuxi
