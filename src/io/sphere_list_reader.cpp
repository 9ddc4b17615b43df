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

// The fields of a line, split at commas, spaces and tabs (a CSV header's names too).
std::vector<std::string_view> fields_of(std::string_view line) {
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

std::optional<double> number_of(std::string_view s) {
  double v = 0;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (error != std::errc{} || end != s.data() + s.size()) return std::nullopt;
  return v;
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
  while (!text.empty()) {
    ++line_number;
    const std::size_t end = std::min(text.find('\n'), text.size());
    std::string_view line = text.substr(0, end);
    text.remove_prefix(std::min(end + 1, text.size()));
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
      line = line.substr(0, hash);
    const std::vector<std::string_view> fields = fields_of(line);
    if (fields.empty()) continue;
    if (header) {
      header = false;
      columns = fields.size();
      const std::array<std::array<std::string_view, 2>, 4> names{
          {{"x", "x"}, {"y", "y"}, {"z", "z"}, {"radius", "r"}}};
      for (std::size_t c = 0; c < 4; ++c) {
        const auto at = std::find_if(fields.begin(), fields.end(), [&](std::string_view f) {
          return f == names[c][0] || f == names[c][1];
        });
        if (at == fields.end())
          fail(fmt::format("the header has no column '{}' (it needs x, y, z and radius)",
                           names[c][0]));
        column[c] = static_cast<std::size_t>(at - fields.begin());
      }
      continue;
    }
    if (format == SphereListFormat::csv ? fields.size() != columns : fields.size() != 4)
      fail(fmt::format("{} fields where the member needs {}", fields.size(),
                       format == SphereListFormat::csv ? columns : 4));
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
