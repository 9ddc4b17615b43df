#include "io/lammps_dump_writer.hpp"

#include "domain/shared_file.hpp"

#include <charconv>
#include <fmt/format.h>
#include <fstream>
#include <stdexcept>
#include <string>

namespace yuxi {

LammpsDumpWriter::LammpsDumpWriter(const std::filesystem::path& path, const Box& box,
                                   std::optional<std::int64_t> resume_after, const Comm& comm,
                                   bool clumps)
    : path_(path), box_(box), comm_(comm), clumps_(clumps) {
  std::string error;
  if (comm_.root()) {
    try {
      start_file(resume_after);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  error = comm_.first_error(error);
  if (!error.empty()) throw std::runtime_error(error);
}

void LammpsDumpWriter::start_file(std::optional<std::int64_t> resume_after) {
  if (resume_after && std::filesystem::exists(path_)) {
    // Keep the complete frames of steps up to the checkpoint; cut the file where the first
    // other frame starts (a later step, or a frame cut short by a crash).
    std::ifstream in(path_, std::ios::binary);
    std::string line;
    std::uintmax_t offset = 0, cut = 0;
    while (std::getline(in, line)) {
      if (line != "ITEM: TIMESTEP") {
        offset += line.size() + 1;
        continue;
      }
      offset += line.size() + 1;
      std::string step_line, item, count_line;
      if (!std::getline(in, step_line) || in.eof()) break;
      offset += step_line.size() + 1;
      if (std::stoll(step_line) > *resume_after) break;
      if (!std::getline(in, item) || !std::getline(in, count_line) || in.eof()) break;
      offset += item.size() + count_line.size() + 2;
      const long long atoms = std::stoll(count_line);
      bool complete = true;
      for (long long k = 0; k < atoms + 5 && complete; ++k) { // bounds (4) and header (1)
        complete = static_cast<bool>(std::getline(in, line)) && !in.eof();
        if (complete) offset += line.size() + 1;
      }
      if (!complete) break;
      cut = offset; // this frame is whole
    }
    in.close();
    std::filesystem::resize_file(path_, cut);
  } else if (!std::ofstream(path_, std::ios::binary | std::ios::trunc)) {
    throw std::runtime_error(fmt::format("cannot write {}", path_.string()));
  }
}

void LammpsDumpWriter::write(const ParticleStore& s, std::int64_t step) {
  const std::vector<std::uint32_t> order = s.owned_in_id_order();
  const std::int64_t total = comm_.sum(static_cast<std::int64_t>(order.size()));
  fmt::memory_buffer buf;
  if (comm_.root()) { // the frame's header
    auto bounds = [&](int a) { return box_.periodic(a) ? "pp" : "ff"; };
    fmt::format_to(std::back_inserter(buf),
                   "ITEM: TIMESTEP\n{}\nITEM: NUMBER OF ATOMS\n{}\nITEM: BOX BOUNDS {} {} {}\n",
                   step, total, bounds(0), bounds(1), bounds(2));
    for (int a = 0; a < 3; ++a)
      fmt::format_to(std::back_inserter(buf), "{:.10g} {:.10g}\n", box_.lo[a], box_.hi[a]);
    fmt::format_to(std::back_inserter(buf),
                   "ITEM: ATOMS id type radius mass x y z vx vy vz omegax omegay omegaz fx fy "
                   "fz{}\n",
                   clumps_ ? " mol" : "");
  }
  // One line per particle, written with std::to_chars: the same text as printf's %.8g and
  // %.10g (the standard defines it so), at about half the cost of fmt's precision formatting,
  // which matters for the paper's 300,000 particles at every snapshot.
  char line[512];
  char* const line_end = line + sizeof line; // (room kept for the separator after each field)
  for (const std::uint32_t i : order) {
    char* at = line;
    const auto integer = [&](long long value) {
      at = std::to_chars(at, line_end - 1, value).ptr;
      *at++ = ' ';
    };
    const auto real = [&](double value, int digits) {
      at = std::to_chars(at, line_end - 1, value, std::chars_format::general, digits).ptr;
      *at++ = ' ';
    };
    integer(s.gid[i]);
    integer(s.material[i] + 1);
    real(s.radius[i], 8);
    real(s.mass[i], 8);
    for (const double c : {s.x[i].x, s.x[i].y, s.x[i].z}) real(c, 10);
    for (const Vec3* vec : {&s.v[i], &s.w[i], &s.f[i]})
      for (const double c : {vec->x, vec->y, vec->z}) real(c, 8);
    if (clumps_) integer(s.body[i] + 1); // (0: no clump, LAMMPS's "no molecule")
    at[-1] = '\n';
    buf.append(line, at);
  }
  SharedFile out(comm_, path_, SharedFile::Mode::append);
  out.write_in_rank_order(out.size_at_open(), std::string_view(buf.data(), buf.size()));
  out.close(false);
}

} // namespace yuxi
