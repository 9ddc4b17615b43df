#include "io/sphere_list_reader.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <optional>

namespace yuxi {
namespace {

// A plain list's fields: split at commas, spaces and tabs, empty ones dropped.
std::vector<std::string_view> plain_fields(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t k = 0;
  const auto separator = [](char c) { return c == ',' || c == ' ' || c == '\t' || c == '\r'; };
  while (k < line.size()) {
    while (k < line.size() && separator(line[k])) ++k;
    const std::size_t from = k;
    while (k < line.size() && !separator(line[k])) ++k;
    if (k > from) out.push_back(line.substr(from, k - from));
  }
  return out;
}

// A CSV row's cells: split at commas only, empty ones kept, each trimmed of spaces, tabs and a
// carriage return and of one pair of double quotes around it.
std::vector<std::string_view> csv_cells(std::string_view line) {
  std::vector<std::string_view> out;
  const auto trim = [](std::string_view c) {
    while (!c.empty() && (c.front() == ' ' || c.front() == '\t')) c.remove_prefix(1);
    while (!c.empty() && (c.back() == ' ' || c.back() == '\t' || c.back() == '\r'))
      c.remove_suffix(1);
    if (c.size() >= 2 && c.front() == '"' && c.back() == '"') c = c.substr(1, c.size() - 2);
    return c;
  };
  for (;;) {
    const std::size_t comma = line.find(',');
    out.push_back(trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) return out;
    line.remove_prefix(comma + 1);
  }
}

std::optional<double> number_of(std::string_view s) {
  if (s.size() > 1 && s.front() == '+') s.remove_prefix(1);
  double v = 0;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (error != std::errc{} || end != s.data() + s.size()) return std::nullopt;
  return v;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

} // namespace

std::vector<SphereMember> parse_sphere_list(std::string_view text, std::string_view source,
                                            SphereListFormat format) {
  std::vector<SphereMember> members;
  // The columns of x, y, z and the radius (a plain list: the first four).
  std::array<std::size_t, 4> column{0, 1, 2, 3};
  std::size_t columns = 4;
  bool header = format == SphereListFormat::csv;
  std::size_t line_number = 0;
  const auto fail = [&](const std::string& message) {
    throw ShapeFileError(fmt::format("{}:{}: {}", source, line_number, message));
  };
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3); // a UTF-8 byte-order mark
  while (!text.empty()) {
    ++line_number;
    const std::size_t end = std::min(text.find('\n'), text.size());
    std::string_view line = text.substr(0, end);
    text.remove_prefix(std::min(end + 1, text.size()));
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
      line = line.substr(0, hash);
    if (plain_fields(line).empty()) continue; // blank
    const std::vector<std::string_view> fields =
        format == SphereListFormat::csv ? csv_cells(line) : plain_fields(line);
    if (header) {
      header = false;
      columns = fields.size();
      const std::array<std::array<std::string_view, 2>, 4> names{
          {{"x", "x"}, {"y", "y"}, {"z", "z"}, {"radius", "r"}}};
      for (std::size_t c = 0; c < 4; ++c) {
        const auto names_c = [&](std::string_view f) {
          const std::string name = lower(f);
          return name == names[c][0] || name == names[c][1];
        };
        const auto at = std::find_if(fields.begin(), fields.end(), names_c);
        if (at == fields.end())
          fail(fmt::format("the header has no column '{}' (it needs x, y, z and radius)",
                           names[c][0]));
        // A second column of the name (or of radius and r both): which one is meant?
        if (std::find_if(at + 1, fields.end(), names_c) != fields.end())
          fail(fmt::format("the header names '{}' twice", names[c][0]));
        column[c] = static_cast<std::size_t>(at - fields.begin());
      }
      continue;
    }
    if (format == SphereListFormat::csv && fields.size() != columns)
      fail(fmt::format("{} cells where the header has {}", fields.size(), columns));
    if (format == SphereListFormat::plain && fields.size() != 4)
      fail(fmt::format("{} fields where a member needs 4 (x y z r)", fields.size()));
    std::array<double, 4> v{};
    for (std::size_t c = 0; c < 4; ++c) {
      const std::string_view f = fields[column[c]];
      const std::optional<double> n = number_of(f);
      if (!n || !std::isfinite(*n))
        fail(fmt::format("'{}' is not a finite number", f.substr(0, 40)));
      v[c] = *n;
    }
    if (!(v[3] > 0)) fail(fmt::format("the radius {} is not positive", v[3]));
    if (members.size() == max_clump_members)
      fail(fmt::format("more than {} members in one clump", max_clump_members));
    members.push_back({{v[0], v[1], v[2]}, v[3]});
  }
  if (header) throw ShapeFileError(fmt::format("{}: empty: no header and no member", source));
  if (members.empty()) throw ShapeFileError(fmt::format("{}: no member sphere", source));
  return members;
}

std::vector<SphereMember> read_sphere_list(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ShapeFileError(fmt::format("{}: cannot open the file", path));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const bool csv = path.size() >= 4 && path.compare(path.size() - 4, 4, ".csv") == 0;
  return parse_sphere_list(text, path, csv ? SphereListFormat::csv : SphereListFormat::plain);
}

} // namespace yuxi
