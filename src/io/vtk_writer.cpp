#include "io/vtk_writer.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <stdexcept>

namespace yuxi {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the VTK writer declares LittleEndian data");

// One appended array: its XML declaration and its bytes.
struct Array {
  std::string type;
  std::string name;
  int components;
  std::vector<char> bytes;
};

template <class T>
Array make_array(std::string type, std::string name, int components, const std::vector<T>& values) {
  Array a{std::move(type), std::move(name), components, {}};
  a.bytes.resize(values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(a.bytes.data(), values.data(), a.bytes.size());
  return a;
}

std::vector<double> flatten(const std::vector<Vec3>& v, std::size_t n) {
  std::vector<double> out(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    out[3 * i] = v[i].x, out[3 * i + 1] = v[i].y, out[3 * i + 2] = v[i].z;
  return out;
}

} // namespace

void write_vtu(const std::filesystem::path& path, const ParticleStore& s) {
  const std::size_t n = s.n_owned();
  std::vector<std::int64_t> id(s.gid.begin(), s.gid.begin() + static_cast<std::ptrdiff_t>(n));
  std::vector<std::int32_t> kind(n), material(n);
  std::vector<std::int64_t> connectivity(n), offsets(n);
  std::vector<std::uint8_t> types(n, 1); // VTK_VERTEX
  for (std::size_t i = 0; i < n; ++i) {
    kind[i] = static_cast<std::int32_t>(s.kind[i]);
    material[i] = s.material[i];
    connectivity[i] = static_cast<std::int64_t>(i);
    offsets[i] = static_cast<std::int64_t>(i + 1);
  }
  std::vector<double> radius(s.radius.begin(), s.radius.begin() + static_cast<std::ptrdiff_t>(n));
  std::vector<double> mass(s.mass.begin(), s.mass.begin() + static_cast<std::ptrdiff_t>(n));
  const std::vector<Array> point_data{make_array("Float64", "radius", 1, radius),
                                      make_array("Float64", "mass", 1, mass),
                                      make_array("Float64", "velocity", 3, flatten(s.v, n)),
                                      make_array("Float64", "angular_velocity", 3, flatten(s.w, n)),
                                      make_array("Float64", "force", 3, flatten(s.f, n)),
                                      make_array("Int64", "id", 1, id),
                                      make_array("Int32", "kind", 1, kind),
                                      make_array("Int32", "material", 1, material)};
  const Array points = make_array("Float64", "Points", 3, flatten(s.x, n));
  const std::vector<Array> cells{make_array("Int64", "connectivity", 1, connectivity),
                                 make_array("Int64", "offsets", 1, offsets),
                                 make_array("UInt8", "types", 1, types)};

  std::string xml;
  std::uint64_t offset = 0;
  auto declare = [&](const Array& a) {
    xml += fmt::format("        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" "
                       "format=\"appended\" offset=\"{}\"/>\n",
                       a.type, a.name, a.components, offset);
    offset += sizeof(std::uint64_t) + a.bytes.size();
  };
  xml += "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
         "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  xml += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", n, n);
  xml += "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
  for (const auto& a : point_data) declare(a);
  xml += "      </PointData>\n      <Points>\n";
  declare(points);
  xml += "      </Points>\n      <Cells>\n";
  for (const auto& a : cells) declare(a);
  xml +=
      "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n_";

  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
  out << xml;
  auto emit = [&](const Array& a) {
    const std::uint64_t size = a.bytes.size();
    out.write(reinterpret_cast<const char*>(&size), sizeof size);
    out.write(a.bytes.data(), static_cast<std::streamsize>(a.bytes.size()));
  };
  for (const auto& a : point_data) emit(a);
  emit(points);
  for (const auto& a : cells) emit(a);
  out << "\n  </AppendedData>\n</VTKFile>\n";
  if (!out) throw std::runtime_error(fmt::format("error while writing {}", path.string()));
}

VtkSeries::VtkSeries(std::filesystem::path folder, std::string stem,
                     std::optional<std::int64_t> resume_after)
    : folder_(std::move(folder)), stem_(std::move(stem)) {
  if (!resume_after) return;
  // Frames are <stem>_<step>.vtu; the .pvd lists them with their times.
  std::ifstream in(folder_ / (stem_ + ".pvd"));
  std::string line;
  const std::string prefix = stem_ + "_";
  while (std::getline(in, line)) {
    const auto t = line.find("timestep=\""), f = line.find("file=\"");
    if (t == std::string::npos || f == std::string::npos) continue;
    const double time = std::stod(line.substr(t + 10));
    const std::string file = line.substr(f + 6, line.find('"', f + 6) - f - 6);
    const std::int64_t step = std::stoll(file.substr(prefix.size()));
    if (step <= *resume_after)
      frames_.emplace_back(time, file);
    else
      std::filesystem::remove(folder_ / file);
  }
  write_collection();
}

void VtkSeries::write(const ParticleStore& s, std::int64_t step, double time) {
  const std::string name = fmt::format("{}_{:09d}.vtu", stem_, step);
  write_vtu(folder_ / name, s);
  frames_.emplace_back(time, name);
  write_collection();
}

void VtkSeries::write_collection() {
  const auto pvd = folder_ / (stem_ + ".pvd");
  const auto tmp = folder_ / (stem_ + ".pvd.tmp");
  {
    std::ofstream out(tmp);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
           "  <Collection>\n";
    for (const auto& [t, file] : frames_)
      out << fmt::format("    <DataSet timestep=\"{:.10g}\" part=\"0\" file=\"{}\"/>\n", t, file);
    out << "  </Collection>\n</VTKFile>\n";
  }
  std::filesystem::rename(tmp, pvd);
}

} // namespace yuxi
