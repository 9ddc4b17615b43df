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

// A per-point array: its bytes for this rank's points (particles or clumps of `Source`) in
// `order`; `first` is the global index of the rank's first point (the points of the ranks
// before it).
template <class Source>
using Packer = std::string (*)(const Source& s, const std::vector<std::uint32_t>& order,
                               std::uint64_t first);

template <class T, class Source, class Get> constexpr Packer<Source> scalar(Get) {
  return [](const Source& s, const std::vector<std::uint32_t>& order, std::uint64_t first) {
    return pack<T>(order, 1, [&](std::size_t k, std::uint32_t i, int) {
      return static_cast<T>(Get{}(s, first + k, i));
    });
  };
}

// A 3-vector (or, with N = 4, a quaternion's w, x, y, z) per point: get(s, i).
template <class Source, class Get, int N = 3> constexpr Packer<Source> vector_of(Get) {
  return [](const Source& s, const std::vector<std::uint32_t>& order, std::uint64_t) {
    return pack<double>(order, N, [&](std::size_t, std::uint32_t i, int c) {
      const auto v = Get{}(s, i);
      if constexpr (N == 4)
        return c == 0 ? v.w : c == 1 ? v.x : c == 2 ? v.y : v.z;
      else
        return v[c];
    });
  };
}

template <std::vector<Vec3> ParticleStore::*field> constexpr Packer<ParticleStore> vector() {
  return vector_of<ParticleStore>(
      [](const ParticleStore& s, std::uint32_t i) { return (s.*field)[i]; });
}

// The appended arrays, in file order: their XML declarations, the bytes of one value and their
// values.
template <class Source> struct ArraySpec {
  const char* type;
  const char* name;
  int components;
  std::size_t value_bytes;
  Packer<Source> values;
  std::uint64_t bytes_per_point() const {
    return static_cast<std::uint64_t>(components) * value_bytes;
  }
};
// (g is the particle's global index in the file, i its index in the store.)
using ParticleArray = ArraySpec<ParticleStore>;
constexpr ParticleArray point_data[] = {
    {"Float64", "radius", 1, 8,
     scalar<double, ParticleStore>(
         [](const ParticleStore& s, std::uint64_t, std::uint32_t i) { return s.radius[i]; })},
    {"Float64", "mass", 1, 8,
     scalar<double, ParticleStore>(
         [](const ParticleStore& s, std::uint64_t, std::uint32_t i) { return s.mass[i]; })},
    {"Float64", "velocity", 3, 8, vector<&ParticleStore::v>()},
    {"Float64", "angular_velocity", 3, 8, vector<&ParticleStore::w>()},
    {"Float64", "force", 3, 8, vector<&ParticleStore::f>()},
    {"Int64", "id", 1, 8,
     scalar<std::int64_t, ParticleStore>(
         [](const ParticleStore& s, std::uint64_t, std::uint32_t i) { return s.gid[i]; })},
    {"Int64", "clump", 1, 8, // the clump a grain is a member of (its id), -1: none
     scalar<std::int64_t, ParticleStore>(
         [](const ParticleStore& s, std::uint64_t, std::uint32_t i) { return s.body[i]; })},
    {"Int32", "kind", 1, 4,
     scalar<std::int32_t, ParticleStore>(
         [](const ParticleStore& s, std::uint64_t, std::uint32_t i) {
           return static_cast<std::int32_t>(s.kind[i]);
         })},
    {"Int32", "material", 1, 4,
     scalar<std::int32_t, ParticleStore>(
         [](const ParticleStore& s, std::uint64_t, std::uint32_t i) { return s.material[i]; })}};

// The clumps' bodies (i their index in the span).
using Bodies = std::span<const ClumpBody>;
using BodyArray = ArraySpec<Bodies>;
template <int axis> Vec3 principal_axis(const ClumpBody& b) {
  Vec3 e;
  e[axis] = 1.0;
  return to_lab(b.q, e);
}
constexpr BodyArray body_data[] = {
    {"Int64", "id", 1, 8, // its first member's id
     scalar<std::int64_t, Bodies>(
         [](Bodies b, std::uint64_t, std::uint32_t i) { return b[i].id; })},
    {"Int32", "shape", 1, 4, // the scene's [[shape]], by index (-1: none named)
     scalar<std::int32_t, Bodies>(
         [](Bodies b, std::uint64_t, std::uint32_t i) { return b[i].shape; })},
    {"Int32", "members", 1, 4,
     scalar<std::int32_t, Bodies>([](Bodies b, std::uint64_t, std::uint32_t i) {
       return static_cast<std::int32_t>(b[i].members.size());
     })},
    {"Int32", "material", 1, 4,
     scalar<std::int32_t, Bodies>(
         [](Bodies b, std::uint64_t, std::uint32_t i) { return b[i].material; })},
    {"Float64", "mass", 1, 8,
     scalar<double, Bodies>([](Bodies b, std::uint64_t, std::uint32_t i) { return b[i].mass; })},
    {"Float64", "principal_moments", 3, 8,
     vector_of<Bodies>([](Bodies b, std::uint32_t i) { return b[i].inertia; })},
    {"Float64", "velocity", 3, 8,
     vector_of<Bodies>([](Bodies b, std::uint32_t i) { return b[i].v; })},
    {"Float64", "angular_velocity", 3, 8,
     vector_of<Bodies>([](Bodies b, std::uint32_t i) { return b[i].angular_velocity(); })},
    {"Float64", "orientation", 4, 8, // the unit quaternion w, x, y, z: body frame -> lab
     vector_of<Bodies, decltype([](Bodies b, std::uint32_t i) { return b[i].q; }), 4>({})},
    // The principal axes in the lab frame, of the smallest moment to the largest (a rod's long
    // axis is axis_1): vectors for ParaView's glyphs.
    {"Float64", "axis_1", 3, 8,
     vector_of<Bodies>([](Bodies b, std::uint32_t i) { return principal_axis<0>(b[i]); })},
    {"Float64", "axis_2", 3, 8,
     vector_of<Bodies>([](Bodies b, std::uint32_t i) { return principal_axis<1>(b[i]); })},
    {"Float64", "axis_3", 3, 8,
     vector_of<Bodies>([](Bodies b, std::uint32_t i) { return principal_axis<2>(b[i]); })},
    {"Float64", "force", 3, 8,
     vector_of<Bodies>([](Bodies b, std::uint32_t i) { return b[i].force; })},
    {"Float64", "torque", 3, 8,
     vector_of<Bodies>([](Bodies b, std::uint32_t i) { return b[i].torque; })}};

// Vertex cell g is point g.
template <class Source>
constexpr ArraySpec<Source> cells[] = {
    {"Int64", "connectivity", 1, 8,
     scalar<std::int64_t, Source>([](const Source&, std::uint64_t g, std::uint32_t) { return g; })},
    {"Int64", "offsets", 1, 8, // where each cell's points end in the connectivity
     scalar<std::int64_t, Source>(
         [](const Source&, std::uint64_t g, std::uint32_t) { return g + 1; })},
    {"UInt8", "types", 1, 1,
     scalar<std::uint8_t, Source>([](const Source&, std::uint64_t, std::uint32_t) {
       return 1; // VTK_VERTEX
     })}};

// One file of vertex cells for all ranks: every appended array holds rank 0's points, then
// rank 1's, ... (each rank's in `order`). Rank 0 writes the XML and each array's size; every
// rank writes its values into each array at its own offset (SharedFile). Collective.
template <class Source>
void write_vertices(const std::filesystem::path& path, const Source& source,
                    const std::vector<std::uint32_t>& order,
                    std::span<const ArraySpec<Source>> point_arrays,
                    const ArraySpec<Source>& positions, const char* scalars, const Comm& comm) {
  const std::uint64_t n = order.size();
  const std::uint64_t total = static_cast<std::uint64_t>(comm.sum(static_cast<std::int64_t>(n)));
  const std::uint64_t first = comm.sum_below(n);

  std::vector<ArraySpec<Source>> arrays(point_arrays.begin(), point_arrays.end());
  arrays.push_back(positions);
  arrays.insert(arrays.end(), std::begin(cells<Source>), std::end(cells<Source>));
  std::vector<std::uint64_t> start; // of each array in the appended data: its size, its values
  std::string xml;
  std::uint64_t offset = 0;
  auto declare = [&](const ArraySpec<Source>& a) {
    xml += fmt::format("        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" "
                       "format=\"appended\" offset=\"{}\"/>\n",
                       a.type, a.name, a.components, offset);
    start.push_back(offset);
    offset += sizeof(std::uint64_t) + total * a.bytes_per_point();
  };
  xml += "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
         "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  xml += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", total, total);
  xml += fmt::format("      <PointData Scalars=\"{}\" Vectors=\"velocity\">\n", scalars);
  for (const auto& a : point_arrays) declare(a);
  xml += "      </PointData>\n      <Points>\n";
  declare(positions);
  xml += "      </Points>\n      <Cells>\n";
  for (const auto& a : cells<Source>) declare(a);
  xml +=
      "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n_";

  SharedFile out(comm, path, SharedFile::Mode::truncate);
  const std::uint64_t data = xml.size(); // where the appended data starts
  if (comm.root()) {
    out.write_at(0, xml);
    for (std::size_t a = 0; a < arrays.size(); ++a) {
      const std::uint64_t size = total * arrays[a].bytes_per_point();
      out.write_at(data + start[a],
                   std::string_view(reinterpret_cast<const char*>(&size), sizeof size));
    }
    out.write_at(data + offset, "\n  </AppendedData>\n</VTKFile>\n");
  }
  for (std::size_t a = 0; a < arrays.size(); ++a)
    out.write_at(data + start[a] + sizeof(std::uint64_t) + first * arrays[a].bytes_per_point(),
                 arrays[a].values(source, order, first));
  out.close(false);
}

} // namespace

void write_vtu(const std::filesystem::path& path, const ParticleStore& s, const Comm& comm) {
  write_vertices<ParticleStore>(path, s, s.owned_in_id_order(), point_data,
                                {"Float64", "Points", 3, 8, vector<&ParticleStore::x>()}, "radius",
                                comm);
}

void write_clumps_vtu(const std::filesystem::path& path, std::span<const ClumpBody> clumps,
                      const Comm& comm) {
  std::vector<std::uint32_t> order(clumps.size()); // (the bodies ascend by id)
  for (std::size_t b = 0; b < order.size(); ++b) order[b] = static_cast<std::uint32_t>(b);
  write_vertices<Bodies>(path, clumps, order, body_data,
                         {"Float64", "Points", 3, 8,
                          vector_of<Bodies>([](Bodies b, std::uint32_t i) { return b[i].x; })},
                         "mass", comm);
}

VtkSeries::VtkSeries(std::filesystem::path folder, std::string stem,
                     std::optional<std::int64_t> resume_after, const Comm& comm)
    : comm_(comm), folder_(std::move(folder)), stem_(std::move(stem)) {
  if (!resume_after || !comm_.root()) return; // (rank 0 keeps the collection)
  // Frames are <stem>_<step>.vtu, walls_<step>.vtp and clumps_<step>.vtu; the .pvd lists them with
  // their times and parts.
  std::ifstream in(folder_ / (stem_ + ".pvd"));
  std::string line;
  while (std::getline(in, line)) {
    const auto t = line.find("timestep=\""), p = line.find("part=\""), f = line.find("file=\"");
    if (t == std::string::npos || f == std::string::npos) continue;
    const double time = std::stod(line.substr(t + 10));
    const int part = p == std::string::npos ? 0 : std::stoi(line.substr(p + 6));
    const std::string file = line.substr(f + 6, line.find('"', f + 6) - f - 6);
    const std::int64_t step = std::stoll(file.substr(file.rfind('_') + 1));
    if (step <= *resume_after) {
      frames_.push_back({time, part, file});
      clumps_shown_ = clumps_shown_ || part == 2;
    } else
      std::filesystem::remove(folder_ / file);
  }
  write_collection();
}

void VtkSeries::write(const ParticleStore& s, std::int64_t step, double time,
                      const WallSurface* walls, std::span<const ClumpBody> clumps) {
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
  // Once a frame showed clumps, every later one has its clumps' part, empty where none is
  // left: ParaView would otherwise go on showing the last clumps it was given.
  if (comm_.any(clumps_shown_ || !clumps.empty())) {
    const std::string clumps_name = fmt::format("clumps_{:09d}.vtu", step);
    write_clumps_vtu(folder_ / clumps_name, clumps, comm_);
    frames_.push_back({time, 2, clumps_name});
    clumps_shown_ = true;
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
