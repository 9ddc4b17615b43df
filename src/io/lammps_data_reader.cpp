#include "io/lammps_data_reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <string>
#include <unordered_map>

namespace yuxi {
namespace {

// Splits a line into whitespace-separated words, dropping a trailing "# comment".
std::vector<std::string_view> words(std::string_view line) {
  if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

class Parser {
public:
  Parser(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

  LammpsData parse() {
    LammpsData d;
    std::int64_t n_atoms = -1;
    bool have_box[3] = {false, false, false};
    std::string_view line;
    // Header: up to the first section keyword.
    std::string_view section;
    while (next(line)) {
      const auto w = words(line);
      if (line_ == 1 || w.empty()) continue; // the first line is a title
      if (is_section(w)) {
        section = w[0];
        break;
      }
      if (w.size() == 2 && w[1] == "atoms") {
        n_atoms = integer(w[0], "number of atoms");
        if (n_atoms < 0) fail("the number of atoms must not be negative");
      } else if (w.size() == 3 && w[1] == "atom" && w[2] == "types") {
        d.n_types = static_cast<int>(integer(w[0], "number of atom types"));
      } else if (w.size() == 4 && w[2].size() == 3 && w[2].substr(1) == "lo" && w[3].size() == 3 &&
                 w[3].substr(1) == "hi" && w[2][0] == w[3][0]) {
        const int a = w[2][0] - 'x'; // "xlo xhi", "ylo yhi", "zlo zhi"
        if (a < 0 || a > 2) fail(fmt::format("unknown box bounds \"{} {}\"", w[2], w[3]));
        d.lo[a] = number(w[0], "box bound");
        d.hi[a] = number(w[1], "box bound");
        if (!(d.hi[a] > d.lo[a])) fail("box bound hi must exceed lo");
        have_box[a] = true;
      } // other header lines (bonds, tilt factors, ...) do not concern spheres
    }
    if (n_atoms < 0) fail("the header does not give the number of atoms");
    for (int a = 0; a < 3; ++a)
      if (!have_box[a]) fail(fmt::format("the header does not give {}lo {}hi", "xyz"[a], "xyz"[a]));
    if (d.n_types < 1) fail("the header does not give the number of atom types");

    std::unordered_map<std::int64_t, std::size_t> index;
    bool have_atoms = false;
    while (!section.empty()) {
      const std::string_view current = section;
      section = {};
      if (current == "Atoms") {
        read_atoms(d, n_atoms, index);
        have_atoms = true;
      } else if (current == "Velocities") {
        if (!have_atoms) fail("Velocities before Atoms");
        read_velocities(d, n_atoms, index);
      }
      // Skip to the next section keyword (also skips the body of ignored sections).
      while (next(line)) {
        const auto w = words(line);
        if (!w.empty() && is_section(w)) {
          section = w[0];
          break;
        }
        if (!w.empty() && (current == "Atoms" || current == "Velocities"))
          fail(fmt::format("more lines in {} than the header's {} atoms", current, n_atoms));
      }
    }
    if (!have_atoms) fail("no Atoms section");
    std::sort(d.atoms.begin(), d.atoms.end(),
              [](const LammpsAtom& a, const LammpsAtom& b) { return a.id < b.id; });
    return d;
  }

private:
  static bool is_section(const std::vector<std::string_view>& w) {
    static const std::string_view keys[] = {"Atoms",  "Velocities", "Masses", "Pair",
                                            "PairIJ", "Bonds",      "Angles", "Ellipsoids"};
    return std::find(std::begin(keys), std::end(keys), w[0]) != std::end(keys) &&
           (w.size() == 1 || w[0] == "Atoms" || w[0] == "Pair" || w[0] == "PairIJ");
  }

  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = text_.find('\n', pos_);
    line = text_.substr(pos_, end == std::string_view::npos ? std::string_view::npos : end - pos_);
    pos_ = end == std::string_view::npos ? text_.size() : end + 1;
    ++line_;
    return true;
  }

  // Reads `count` non-empty lines of a section.
  template <class F> void body(std::int64_t count, const char* name, F&& each) {
    std::string_view line;
    std::int64_t read = 0;
    while (read < count) {
      if (!next(line)) fail(fmt::format("{} ends after {} of {} lines", name, read, count));
      const auto w = words(line);
      if (w.empty()) continue;
      if (is_section(w))
        fail(fmt::format("{} holds {} lines; the header announces {} atoms", name, read, count));
      each(w);
      ++read;
    }
  }

  void read_atoms(LammpsData& d, std::int64_t n,
                  std::unordered_map<std::int64_t, std::size_t>& index) {
    // The header's count is not trusted for memory: an Atoms line takes at least 14 bytes.
    d.atoms.reserve(std::min(static_cast<std::size_t>(n), text_.size() / 14 + 1));
    body(n, "Atoms", [&](const std::vector<std::string_view>& w) {
      if (w.size() != 7 && w.size() != 10)
        fail(fmt::format("an Atoms line of atom_style sphere has 7 or 10 columns (id type "
                         "diameter density x y z [ix iy iz]), this one {}",
                         w.size()));
      LammpsAtom a;
      a.id = integer(w[0], "atom id");
      a.type = static_cast<int>(integer(w[1], "atom type"));
      if (a.type < 1 || a.type > d.n_types)
        fail(fmt::format("atom type {} outside 1..{}", a.type, d.n_types));
      a.diameter = number(w[2], "diameter");
      a.density = number(w[3], "density");
      if (!(a.diameter > 0) || !(a.density > 0)) fail("diameter and density must be > 0");
      for (int k = 0; k < 3; ++k) a.x[k] = number(w[4 + k], "position");
      if (!index.emplace(a.id, d.atoms.size()).second)
        fail(fmt::format("atom id {} appears twice", a.id));
      d.atoms.push_back(a);
    });
  }

  void read_velocities(LammpsData& d, std::int64_t n,
                       std::unordered_map<std::int64_t, std::size_t>& index) {
    body(n, "Velocities", [&](const std::vector<std::string_view>& w) {
      if (w.size() != 7)
        fail(fmt::format("a Velocities line of atom_style sphere has 7 columns (id vx vy vz wx "
                         "wy wz), this one {}",
                         w.size()));
      const auto it = index.find(integer(w[0], "atom id"));
      if (it == index.end()) fail(fmt::format("velocity of an unknown atom {}", w[0]));
      LammpsAtom& a = d.atoms[it->second];
      for (int k = 0; k < 3; ++k) {
        a.v[k] = number(w[1 + k], "velocity");
        a.w[k] = number(w[4 + k], "angular velocity");
      }
    });
  }

  std::int64_t integer(std::string_view s, const char* what) {
    std::int64_t v = 0;
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || p != s.data() + s.size())
      fail(fmt::format("{} \"{}\" is not an integer", what, s));
    return v;
  }

  double number(std::string_view s, const char* what) {
    double v = 0;
    const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || p != s.data() + s.size() || !std::isfinite(v))
      fail(fmt::format("{} \"{}\" is not a finite number", what, s));
    return v;
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw DataFileError(fmt::format("{}:{}: {}", source_, line_, message));
  }

  std::string_view text_;
  std::string source_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

} // namespace

LammpsData parse_lammps_data(std::string_view text, const std::string& source) {
  return Parser(text, source).parse();
}

LammpsData read_lammps_data(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataFileError(fmt::format("{}: cannot open the LAMMPS data file", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_lammps_data(text.str(), path.string());
}

} // namespace yuxi
