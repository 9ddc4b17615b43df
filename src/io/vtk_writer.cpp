#include "io/vtk_writer.hpp"

#include "domain/shared_file.hpp"

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

// The values of one array for this rank's particles, `order[k]` for k = 0, 1, ...: get(k, i, c)
// gives component c of particle i = order[k], as a T.
template <class T, class Get>
std::string pack(const std::vector<std::uint32_t>& order, int components, Get get) {
  std::string out(order.size() * static_cast<std::size_t>(components) * sizeof(T), '\0');
  char* at = out.data();
  for (std::size_t k = 0; k < order.size(); ++k)
    for (int c = 0; c < components; ++c) {
      const T v = get(k, order[k], c);
      std::memcpy(at, &v, sizeof v);
      at += sizeof v;
    }
  return out;
}

// A per-particle array: its bytes for this rank's particles in `order`; `first` is the global
// index of the rank's first particle (the cells of the ranks before it).
using Packer = std::string (*)(const ParticleStore& s, const std::vector<std::uint32_t>& order,
                               std::uint64_t first);

template <class T, class Get> constexpr Packer scalar(Get) {
  return [](const ParticleStore& s, const std::vector<std::uint32_t>& order, std::uint64_t first) {
    return pack<T>(order, 1, [&](std::size_t k, std::uint32_t i, int) {
      return static_cast<T>(Get{}(s, first + k, i));
    });
  };
}

template <std::vector<Vec3> ParticleStore::*field> constexpr Packer vector() {
  return [](const ParticleStore& s, const std::vector<std::uint32_t>& order, std::uint64_t) {
    return pack<double>(order, 3,
                        [&](std::size_t, std::uint32_t i, int c) { return (s.*field)[i][c]; });
  };
}

// The appended arrays, in file order: their XML declarations, the bytes of one value and their
// values.
struct ArraySpec {
  const char* type;
  const char* name;
  int components;
  std::size_t value_bytes;
  Packer values;
  std::uint64_t bytes_per_particle() const {
    return static_cast<std::uint64_t>(components) * value_bytes;
  }
};
// (g is the particle's global index in the file, i its index in the store.)
constexpr ArraySpec point_data[] = {
    {"Float64", "radius", 1, 8,
     scalar<double>(
         [](const ParticleStore& s, std::uint64_t, std::uint32_t i) { return s.radius[i]; })},
    {"Float64", "mass", 1, 8,
     scalar<double>(
         [](const ParticleStore& s, std::uint64_t, std::uint32_t i) { return s.mass[i]; })},
    {"Float64", "velocity", 3, 8, vector<&ParticleStore::v>()},
    {"Float64", "angular_velocity", 3, 8, vector<&ParticleStore::w>()},
    {"Float64", "force", 3, 8, vector<&ParticleStore::f>()},
    {"Int64", "id", 1, 8,
     scalar<std::int64_t>(
         [](const ParticleStore& s, std::uint64_t, std::uint32_t i) { return s.gid[i]; })},
    {"Int64", "clump", 1, 8, // the clump a grain is a member of (its id), -1: none
     scalar<std::int64_t>(
         [](const ParticleStore& s, std::uint64_t, std::uint32_t i) { return s.body[i]; })},
    {"Int32", "kind", 1, 4,
     scalar<std::int32_t>([](const ParticleStore& s, std::uint64_t, std::uint32_t i) {
       return static_cast<std::int32_t>(s.kind[i]);
     })},
    {"Int32", "material", 1, 4,
     scalar<std::int32_t>(
         [](const ParticleStore& s, std::uint64_t, std::uint32_t i) { return s.material[i]; })}};
constexpr ArraySpec points{"Float64", "Points", 3, 8, vector<&ParticleStore::x>()};
constexpr ArraySpec cells[] = {
    {"Int64", "connectivity", 1, 8, // vertex cell g is point g
     scalar<std::int64_t>([](const ParticleStore&, std::uint64_t g, std::uint32_t) { return g; })},
    {"Int64", "offsets", 1, 8, // where each cell's points end in the connectivity
     scalar<std::int64_t>(
         [](const ParticleStore&, std::uint64_t g, std::uint32_t) { return g + 1; })},
    {"UInt8", "types", 1, 1,
     scalar<std::uint8_t>([](const ParticleStore&, std::uint64_t, std::uint32_t) {
       return 1; // VTK_VERTEX
     })}};

} // namespace

void write_vtu(const std::filesystem::path& path, const ParticleStore& s, const Comm& comm) {
  // One file for all ranks: every appended array holds rank 0's particles, then rank 1's, ...
  // (each rank's in ascending id). Rank 0 writes the XML and each array's size; every rank
  // writes its values into each array at its own offset (SharedFile).
  const std::vector<std::uint32_t> order = s.owned_in_id_order();
  const std::uint64_t n = order.size();
  const std::uint64_t total = static_cast<std::uint64_t>(comm.sum(static_cast<std::int64_t>(n)));
  const std::uint64_t first = comm.sum_below(n);

  std::vector<ArraySpec> arrays(std::begin(point_data), std::end(point_data));
  arrays.push_back(points);
  arrays.insert(arrays.end(), std::begin(cells), std::end(cells));
  std::vector<std::uint64_t> start; // of each array in the appended data: its size, its values
  std::string xml;
  std::uint64_t offset = 0;
  auto declare = [&](const ArraySpec& a) {
    xml += fmt::format("        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" "
                       "format=\"appended\" offset=\"{}\"/>\n",
                       a.type, a.name, a.components, offset);
    start.push_back(offset);
    offset += sizeof(std::uint64_t) + total * a.bytes_per_particle();
  };
  xml += "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
         "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  xml += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", total, total);
  xml += "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
  for (const auto& a : point_data) declare(a);
  xml += "      </PointData>\n      <Points>\n";
  declare(points);
  xml += "      </Points>\n      <Cells>\n";
  for (const auto& a : cells) declare(a);
  xml +=
      "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n_";

  SharedFile out(comm, path, SharedFile::Mode::truncate);
  const std::uint64_t data = xml.size(); // where the appended data starts
  if (comm.root()) {
    out.write_at(0, xml);
    for (std::size_t a = 0; a < arrays.size(); ++a) {
      const std::uint64_t size = total * arrays[a].bytes_per_particle();
      out.write_at(data + start[a],
                   std::string_view(reinterpret_cast<const char*>(&size), sizeof size));
    }
    out.write_at(data + offset, "\n  </AppendedData>\n</VTKFile>\n");
  }
  for (std::size_t a = 0; a < arrays.size(); ++a)
    out.write_at(data + start[a] + sizeof(std::uint64_t) + first * arrays[a].bytes_per_particle(),
                 arrays[a].values(s, order, first));
  out.close(false);
}

VtkSeries::VtkSeries(std::filesystem::path folder, std::string stem,
                     std::optional<std::int64_t> resume_after, const Comm& comm)
    : comm_(comm), folder_(std::move(folder)), stem_(std::move(stem)) {
  if (!resume_after || !comm_.root()) return; // (rank 0 keeps the collection)
  // Frames are <stem>_<step>.vtu and walls_<step>.vtp; the .pvd lists them with their times
  // and parts.
  std::ifstream in(folder_ / (stem_ + ".pvd"));
  std::string line;
  while (std::getline(in, line)) {
    const auto t = line.find("timestep=\""), p = line.find("part=\""), f = line.find("file=\"");
    if (t == std::string::npos || f == std::string::npos) continue;
    const double time = std::stod(line.substr(t + 10));
    const int part = p == std::string::npos ? 0 : std::stoi(line.substr(p + 6));
    const std::string file = line.substr(f + 6, line.find('"', f + 6) - f - 6);
    const std::int64_t step = std::stoll(file.substr(file.rfind('_') + 1));
    if (step <= *resume_after)
      frames_.push_back({time, part, file});
    else
      std::filesystem::remove(folder_ / file);
  }
  write_collection();
}

void VtkSeries::write(const ParticleStore& s, std::int64_t step, double time,
                      const WallSurface* walls) {
  const std::string name = fmt::format("{}_{:09d}.vtu", stem_, step);
  write_vtu(folder_ / name, s, comm_);
  frames_.push_back({time, 0, name});
  if (walls) {
    // Rank 0 writes them; a failure there stops every rank.
    const std::string walls_name = fmt::format("walls_{:09d}.vtp", step);
    std::string error;
    if (comm_.root()) {
      try {
        write_vtp(folder_ / walls_name, *walls);
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    error = comm_.first_error(error);
    if (!error.empty()) throw std::runtime_error(error);
    frames_.push_back({time, 1, walls_name});
  }
  write_collection();
}

void VtkSeries::write_collection() {
  if (!comm_.root()) return;
  const auto pvd = folder_ / (stem_ + ".pvd");
  const auto tmp = folder_ / (stem_ + ".pvd.tmp");
  {
    std::ofstream out(tmp);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
           "  <Collection>\n";
    for (const auto& [t, part, file] : frames_)
      out << fmt::format("    <DataSet timestep=\"{:.10g}\" part=\"{}\" file=\"{}\"/>\n", t, part,
                         file);
    out << "  </Collection>\n</VTKFile>\n";
  }
  std::filesystem::rename(tmp, pvd);
}

} // namespace yuxi
