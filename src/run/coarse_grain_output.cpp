#include "run/coarse_grain_output.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
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

analysis::CgParts contact_parts(const CoarseGrainSpec& spec) {
  return spec.contacts ? analysis::parts_for(spec.fields) : analysis::CgParts{false, false, false};
}

std::string CoarseGrainOutput::extension(const Table& t) {
  return t.cylinder ? ".vts" : ".vti";
}

CoarseGrainOutput::CoarseGrainOutput(std::vector<CoarseGrainSpec> specs, const Simulation& sim,
                                     std::filesystem::path dir, double dt)
    : dt_(dt), root_(sim.comm().root()) {
  const Box& box = sim.config().box;
  for (CoarseGrainSpec& spec : specs) {
    Table t;
    t.settings.kind = kind_of(spec.function);
    t.settings.width = spec.width;
    t.settings.cutoff = spec.cutoff;
    t.settings.parts = contact_parts(spec);
    if (spec.cylindrical) {
      analysis::CgCylinderSettings c;
      c.kind = t.settings.kind;
      c.width = spec.width;
      c.cutoff = spec.cutoff;
      c.parts = t.settings.parts;
      c.grid = {spec.axis_x, spec.axis_y, spec.lo.x,        spec.hi.x,       spec.lo.z,
                spec.hi.z,   spec.n,      spec.averaged[1], spec.averaged[2]};
      c.grid.check();
      t.cylinder = c;
    } else {
      t.settings.grid.lo = spec.lo;
      t.settings.grid.hi = spec.hi;
      t.settings.grid.n = spec.n;
      t.settings.grid.averaged = spec.averaged;
      // A periodic axis wraps where the grid spans the box along it.
      for (int a = 0; a < 3; ++a)
        t.settings.grid.periodic[static_cast<std::size_t>(a)] =
            box.periodic(a) && spec.lo[a] == box.lo[a] && spec.hi[a] == box.hi[a];
      t.settings.grid.check();
    }
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
    return t.settings.parts.any() && step > 0 && (step % t.every == 0 || step % t.sample == 0);
  });
}

void CoarseGrainOutput::sample(const Simulation& sim) {
  const std::int64_t step = sim.step_count();
  bool gathered = false;
  for (Table& t : tables_) {
    const bool write_now = step % t.every == 0, sample_now = step % t.sample == 0 || write_now;
    if (!sample_now) continue;
    if (!gathered) input_.gather(sim), gathered = true;
    const std::span<const analysis::CgContact> used =
        t.settings.parts.any() ? std::span<const analysis::CgContact>(input_.contacts)
                               : std::span<const analysis::CgContact>();
    const std::vector<double> sums =
        t.cylinder ? analysis::coarse_grain_sums(input_.grains(), used, *t.cylinder)
                   : analysis::coarse_grain_sums(input_.grains(), used, t.settings);
    if (t.sums.empty()) t.sums.assign(sums.size(), 0.0);
    for (std::size_t k = 0; k < sums.size(); ++k) t.sums[k] += sums[k];
    ++t.samples;
    if (!write_now) continue;
    // The mean of the samples since the last write (one sample without a time average).
    sim.comm().sum(t.sums.data(), static_cast<int>(t.sums.size()));
    for (double& total : t.sums) total /= static_cast<double>(t.samples);
    if (root_) write(t, analysis::coarse_grain_fields(t.sums, t.points()), step);
    t.sums.assign(t.sums.size(), 0.0);
    t.samples = 0;
  }
}

void CoarseGrainOutput::write(Table& t, const analysis::CgFields& f, std::int64_t step) const {
  const std::string stem = fmt::format("{}_{:09d}", t.spec.name, step);
  // The table's fields, in the order it names them (the reader checked the names).
  std::vector<analysis::CgNamedField> columns;
  const std::vector<analysis::CgNamedField> all = analysis::named_fields(f);
  for (const std::string& name : t.spec.fields)
    columns.push_back(*std::find_if(
        all.begin(), all.end(), [&](const analysis::CgNamedField& c) { return c.name == name; }));
  // The points, first axis fastest: their grid coordinates (x, y, z or r, theta, z) and their
  // places in space.
  const std::array<int, 3> n = t.cylinder ? t.cylinder->grid.n : t.settings.grid.n;
  const auto coordinates = [&t](int i, int j, int k) -> Vec3 {
    if (!t.cylinder) {
      const analysis::CgGrid& g = t.settings.grid;
      return {g.coordinate(0, i), g.coordinate(1, j), g.coordinate(2, k)};
    }
    const analysis::CgCylinder& g = t.cylinder->grid;
    return {g.r(i), g.theta(j), g.z(k)};
  };
  const auto place = [&t, &coordinates](int i, int j, int k) -> Vec3 {
    const Vec3 c = coordinates(i, j, k);
    if (!t.cylinder) return c;
    const analysis::CgCylinder& g = t.cylinder->grid;
    // A circle's mean is drawn in the plane y = y0, at x = x0 + r.
    const double angle = g.theta_averaged ? 0.0 : c.y;
    return {g.x0 + c.x * std::cos(angle), g.y0 + c.x * std::sin(angle), c.z};
  };

  // CSV: the point, then each field's components. Both files are formatted into one buffer
  // each, without a string a value.
  {
    fmt::memory_buffer out;
    fmt::format_to(std::back_inserter(out), "{}", t.cylinder ? "r,theta,z" : "x,y,z");
    for (std::size_t c = 0; c < columns.size(); ++c)
      for (const std::string& name : column_names(t.spec.fields[c], columns[c].components))
        fmt::format_to(std::back_inserter(out), ",{}", name);
    out.push_back('\n');
    std::size_t p = 0;
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i, ++p) {
          const Vec3 c = coordinates(i, j, k);
          fmt::format_to(std::back_inserter(out), "{:.10g},{:.10g},{:.10g}", c.x, c.y, c.z);
          for (const analysis::CgNamedField& col : columns)
            for (int q = 0; q < col.components; ++q)
              fmt::format_to(std::back_inserter(out), ",{:.10g}",
                             (*col.values)[p * col.components + q]);
          out.push_back('\n');
        }
    std::ofstream(t.folder / (stem + ".csv"))
        .write(out.data(), static_cast<std::streamsize>(out.size()));
  }
  // VTK: an image (the points at the cells' centres) on a Cartesian grid, a structured grid of
  // the points' places on a cylindrical one; first axis fastest.
  {
    fmt::memory_buffer out;
    const auto extent = fmt::format("0 {} 0 {} 0 {}", n[0] - 1, n[1] - 1, n[2] - 1);
    const char* type = t.cylinder ? "StructuredGrid" : "ImageData";
    fmt::format_to(std::back_inserter(out),
                   "<?xml version=\"1.0\"?>\n"
                   "<VTKFile type=\"{}\" version=\"1.0\" byte_order=\"LittleEndian\">\n",
                   type);
    if (t.cylinder) {
      fmt::format_to(std::back_inserter(out),
                     "<StructuredGrid WholeExtent=\"{}\">\n<Piece Extent=\"{}\">\n<Points>\n"
                     "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n",
                     extent, extent);
      for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
          for (int i = 0; i < n[0]; ++i) {
            const Vec3 x = place(i, j, k);
            fmt::format_to(std::back_inserter(out), "{:.10g} {:.10g} {:.10g} ", x.x, x.y, x.z);
          }
      fmt::format_to(std::back_inserter(out), "\n</DataArray>\n</Points>\n<PointData>\n");
    } else {
      const analysis::CgGrid& g = t.settings.grid;
      fmt::format_to(std::back_inserter(out),
                     "<ImageData WholeExtent=\"{}\" Origin=\"{:.10g} {:.10g} {:.10g}\" "
                     "Spacing=\"{:.10g} {:.10g} {:.10g}\">\n<Piece Extent=\"{}\">\n<PointData>\n",
                     extent, g.coordinate(0, 0), g.coordinate(1, 0), g.coordinate(2, 0),
                     g.spacing(0), g.spacing(1), g.spacing(2), extent);
    }
    for (std::size_t c = 0; c < columns.size(); ++c) {
      fmt::format_to(std::back_inserter(out),
                     "<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" "
                     "format=\"ascii\">\n",
                     t.spec.fields[c], columns[c].components);
      for (const double value : *columns[c].values)
        fmt::format_to(std::back_inserter(out), "{:.10g} ", value);
      fmt::format_to(std::back_inserter(out), "\n</DataArray>\n");
    }
    fmt::format_to(std::back_inserter(out), "</PointData>\n</Piece>\n</{}>\n</VTKFile>\n", type);
    std::ofstream(t.folder / (stem + extension(t)))
        .write(out.data(), static_cast<std::streamsize>(out.size()));
  }
  // The series: every sample of the folder, by step (the files of an earlier run that this one
  // resumes included: the folder is read once, at the first write).
  if (!t.listed) {
    const std::string prefix = t.spec.name + "_";
    for (const auto& entry : std::filesystem::directory_iterator(t.folder)) {
      const std::string file = entry.path().filename().string();
      if (entry.path().extension() == extension(t) && file.rfind(prefix, 0) == 0)
        t.written.insert(std::stoll(file.substr(prefix.size(), 9)));
    }
    t.listed = true;
  }
  t.written.insert(step);
  const std::set<std::int64_t>& steps = t.written;
  std::ofstream pvd(t.folder / (t.spec.name + ".pvd"));
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n<Collection>\n";
  for (const std::int64_t s : steps)
    pvd << fmt::format("<DataSet timestep=\"{:.10g}\" file=\"{}_{:09d}{}\"/>\n",
                       static_cast<double>(s) * dt_, t.spec.name, s, extension(t));
  pvd << "</Collection>\n</VTKFile>\n";
}

} // namespace yuxi
