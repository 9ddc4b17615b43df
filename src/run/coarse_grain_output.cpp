#include "run/coarse_grain_output.hpp"

#include "core/ball_volume.hpp"
#include "run/coarse_grain_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <string>

namespace yuxi {
namespace {

analysis::CgKind kind_of(const std::string& function) {
  if (function == "lucy") return analysis::CgKind::lucy;
  if (function == "bins") return analysis::CgKind::bins;
  return analysis::CgKind::gaussian;
}

// The CSV column names of a field: name, name_x..., name_xx, name_xy, ...
std::vector<std::string> column_names(const std::string& name, int components) {
  static constexpr const char* axis[] = {"x", "y", "z"};
  if (components == 1) return {name};
  std::vector<std::string> out;
  if (components == 3)
    for (const char* a : axis) out.push_back(name + "_" + a);
  else
    for (const char* a : axis)
      for (const char* b : axis) out.push_back(name + "_" + a + b);
  return out;
}

} // namespace

CoarseGrainOutput::CoarseGrainOutput(std::vector<CoarseGrainSpec> specs, const Simulation& sim,
                                     std::filesystem::path dir, double dt)
    : dt_(dt), root_(sim.comm().root()) {
  const Box& box = sim.config().box;
  for (CoarseGrainSpec& spec : specs) {
    Table t;
    t.settings.kind = kind_of(spec.function);
    t.settings.width = spec.width;
    t.settings.cutoff = spec.cutoff;
    t.settings.grid.lo = spec.lo;
    t.settings.grid.hi = spec.hi;
    t.settings.grid.n = spec.n;
    t.settings.grid.averaged = spec.averaged;
    // A periodic axis wraps where the grid spans the box along it.
    for (int a = 0; a < 3; ++a)
      t.settings.grid.periodic[static_cast<std::size_t>(a)] =
          box.periodic(a) && spec.lo[a] == box.lo[a] && spec.hi[a] == box.hi[a];
    t.settings.grid.check();
    t.every = std::max<std::int64_t>(1, std::llround(spec.interval / dt));
    t.sample = spec.average_every > 0 ? spec.average_every : t.every;
    t.folder = dir / "coarse_grain" / spec.name;
    if (root_) std::filesystem::create_directories(t.folder);
    t.spec = std::move(spec);
    tables_.push_back(std::move(t));
  }
}

std::int64_t CoarseGrainOutput::next_sample_after(std::int64_t step) const {
  std::int64_t next = std::numeric_limits<std::int64_t>::max();
  for (const Table& t : tables_) {
    next = std::min(next, (step / t.every + 1) * t.every);
    next = std::min(next, (step / t.sample + 1) * t.sample);
  }
  return next;
}

bool CoarseGrainOutput::needs_contacts_at(std::int64_t step) const {
  return std::any_of(tables_.begin(), tables_.end(), [&](const Table& t) {
    return t.spec.contacts && step > 0 && (step % t.every == 0 || step % t.sample == 0);
  });
}

void CoarseGrainOutput::sample(const Simulation& sim) {
  const std::int64_t step = sim.step_count();
  std::vector<Vec3> x, v;
  std::vector<double> mass, volume;
  std::vector<analysis::CgContact> contacts;
  bool gathered = false;
  for (Table& t : tables_) {
    const bool write_now = step % t.every == 0, sample_now = step % t.sample == 0 || write_now;
    if (!sample_now) continue;
    if (!gathered) {
      const ParticleStore& p = sim.particles();
      for (std::size_t i = 0; i < p.n_owned(); ++i) {
        if (!p.is_grain(i)) continue;
        x.push_back(p.x[i]), v.push_back(p.v[i]), mass.push_back(p.mass[i]);
        volume.push_back(ball_volume(p.radius[i]));
      }
      if (sim.contact_record().enabled) contacts = coarse_grain_contacts(sim);
      gathered = true;
    }
    const analysis::CgGrains grains{x, v, mass, volume};
    const std::span<const analysis::CgContact> used =
        t.spec.contacts ? std::span<const analysis::CgContact>(contacts)
                        : std::span<const analysis::CgContact>();
    const std::vector<double> sums = analysis::coarse_grain_sums(grains, used, t.settings);
    if (t.sums.empty()) t.sums.assign(sums.size(), 0.0);
    for (std::size_t k = 0; k < sums.size(); ++k) t.sums[k] += sums[k];
    ++t.samples;
    if (!write_now) continue;
    // The mean of the samples since the last write (one sample without a time average).
    sim.comm().sum(t.sums.data(), static_cast<int>(t.sums.size()));
    for (double& total : t.sums) total /= static_cast<double>(t.samples);
    if (root_) write(t, analysis::coarse_grain_fields(t.sums, t.settings.grid), step);
    t.sums.assign(t.sums.size(), 0.0);
    t.samples = 0;
  }
}

void CoarseGrainOutput::write(const Table& t, const analysis::CgFields& f,
                              std::int64_t step) const {
  const analysis::CgGrid& g = t.settings.grid;
  const std::string stem = fmt::format("{}_{:09d}", t.spec.name, step);
  // The table's fields, in the order it names them (the reader checked the names).
  std::vector<analysis::CgNamedField> columns;
  const std::vector<analysis::CgNamedField> all = analysis::named_fields(f);
  for (const std::string& name : t.spec.fields)
    columns.push_back(*std::find_if(
        all.begin(), all.end(), [&](const analysis::CgNamedField& c) { return c.name == name; }));

  // CSV: the point (x fastest), then each field's components.
  {
    std::ofstream csv(t.folder / (stem + ".csv"));
    csv << "x,y,z";
    for (std::size_t c = 0; c < columns.size(); ++c)
      for (const std::string& n : column_names(t.spec.fields[c], columns[c].components))
        csv << ',' << n;
    csv << '\n';
    for (int k = 0; k < g.n[2]; ++k)
      for (int j = 0; j < g.n[1]; ++j)
        for (int i = 0; i < g.n[0]; ++i) {
          const std::size_t p = g.index(i, j, k);
          csv << fmt::format("{:.10g},{:.10g},{:.10g}", g.coordinate(0, i), g.coordinate(1, j),
                             g.coordinate(2, k));
          for (const analysis::CgNamedField& col : columns)
            for (int q = 0; q < col.components; ++q)
              csv << fmt::format(",{:.10g}", (*col.values)[p * col.components + q]);
          csv << '\n';
        }
  }
  // VTK image data: the points at the cells' centres, x fastest.
  {
    std::ofstream vti(t.folder / (stem + ".vti"));
    const auto extent = fmt::format("0 {} 0 {} 0 {}", g.n[0] - 1, g.n[1] - 1, g.n[2] - 1);
    vti << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
        << fmt::format("<ImageData WholeExtent=\"{}\" Origin=\"{:.10g} {:.10g} {:.10g}\" "
                       "Spacing=\"{:.10g} {:.10g} {:.10g}\">\n",
                       extent, g.coordinate(0, 0), g.coordinate(1, 0), g.coordinate(2, 0),
                       g.spacing(0), g.spacing(1), g.spacing(2))
        << fmt::format("<Piece Extent=\"{}\">\n<PointData>\n", extent);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      vti << fmt::format("<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" "
                         "format=\"ascii\">\n",
                         t.spec.fields[c], columns[c].components);
      for (const double value : *columns[c].values) vti << fmt::format("{:.10g} ", value);
      vti << "\n</DataArray>\n";
    }
    vti << "</PointData>\n</Piece>\n</ImageData>\n</VTKFile>\n";
  }
  // The series: every sample of the folder, by step.
  std::vector<std::int64_t> steps;
  for (const auto& entry : std::filesystem::directory_iterator(t.folder)) {
    const std::string file = entry.path().filename().string();
    const std::string prefix = t.spec.name + "_";
    if (entry.path().extension() == ".vti" && file.rfind(prefix, 0) == 0)
      steps.push_back(std::stoll(file.substr(prefix.size(), 9)));
  }
  std::sort(steps.begin(), steps.end());
  std::ofstream pvd(t.folder / (t.spec.name + ".pvd"));
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n<Collection>\n";
  for (const std::int64_t s : steps)
    pvd << fmt::format("<DataSet timestep=\"{:.10g}\" file=\"{}_{:09d}.vti\"/>\n",
                       static_cast<double>(s) * dt_, t.spec.name, s);
  pvd << "</Collection>\n</VTKFile>\n";
}

} // namespace yuxi
